#include "sim/execution/frame_result.h"

#include <algorithm>

namespace rtc {

namespace {

template <class T>
void size_items(UninitializedVector<T>& v, std::size_t items, std::size_t first, std::size_t last) {
    v.resize(items);
    std::fill(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(first, items)), T{});
    std::fill(v.begin() + static_cast<std::ptrdiff_t>(std::min(last, items)), v.end(), T{});
}

}  // namespace

void size_for_band(UninitializedVector<RayCounts>& v, std::size_t items, std::size_t first, std::size_t last) {
    size_items(v, items, first, last);
}

void size_for_band(UninitializedVector<Vec3>& v, std::size_t items, std::size_t first, std::size_t last) {
    size_items(v, items, first, last);
}

void finish_band(FrameResult& out, std::size_t tasks, std::size_t first, std::size_t last,
                 std::size_t items_per_task, std::size_t items) {
    out.task_count = tasks;
    out.task_begin = first;
    out.task_end = last;
    out.item_begin = std::min(items, first * items_per_task);
    out.item_end = std::min(items, last * items_per_task);
}

}  // namespace rtc
