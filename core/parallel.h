// Running independent work items on all cores, with no dependency beyond
// std::thread: indices are handed out in chunks from one atomic counter, so
// uneven items balance themselves. Callers that write results into per-index
// slots get the same output whatever the thread count or the scheduling.
// The threads are a pool kept for the process (see run_on_threads).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>

namespace rtc {

// Cores available to this process (at least 1).
[[nodiscard]] unsigned hardware_threads();

namespace detail {

// Runs body(context, t) once for each t in [0, threads) at the same time:
// t = 0 on the calling thread, the others on the process's pool of threads,
// started at the first call that needs them and kept waiting for the next
// (starting threads per call cost 29 us each here, 210-225 us under
// SCHED_FIFO, and a build makes two calls per node of its top). Where the
// pool is in use (a call from inside another's body, or two callers at
// once), fresh threads run it as before. Fewer than `threads` run when the
// system has no more; body must not throw.
void run_on_threads(unsigned threads, void (*body)(const void* context, unsigned thread_id) noexcept,
                    const void* context);

}  // namespace detail

// Calls fn(index, thread_id) once for every index in [0, count), on up to
// `threads` threads (0 = hardware_threads()); thread_id < that number, so it
// can index per-thread scratch. The calling thread takes part as thread 0 and
// a single thread runs inline, creating none. `grain` is the number of
// consecutive indices taken at once (0 = automatic, about 8 chunks per thread).
// The first exception thrown by fn stops the hand-out of further chunks and is
// rethrown here once every thread has finished.
template <class F>
void parallel_for(std::size_t count, unsigned threads, F&& fn, std::size_t grain = 0) {
    if (count == 0) return;
    if (threads == 0) threads = hardware_threads();
    if (grain == 0) grain = std::max<std::size_t>(1, count / (std::size_t{threads} * 8));
    const std::size_t chunks = (count + grain - 1) / grain;
    threads = static_cast<unsigned>(std::min<std::size_t>(threads, chunks));
    if (threads <= 1) {
        for (std::size_t i = 0; i < count; ++i) fn(i, 0u);
        return;
    }

    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex error_mutex;
    const auto worker = [&](unsigned thread_id) noexcept {
        try {
            while (!failed.load(std::memory_order_relaxed)) {
                const std::size_t begin = next.fetch_add(grain, std::memory_order_relaxed);
                if (begin >= count) break;
                const std::size_t end = std::min(count, begin + grain);
                for (std::size_t i = begin; i < end; ++i) fn(i, thread_id);
            }
        } catch (...) {
            const std::lock_guard lock(error_mutex);
            if (!error) error = std::current_exception();
            failed.store(true, std::memory_order_relaxed);
        }
    };
    using Worker = decltype(worker);
    detail::run_on_threads(
        threads, [](const void* w, unsigned thread_id) noexcept { (*static_cast<const Worker*>(w))(thread_id); },
        &worker);
    if (error) std::rethrow_exception(error);
}

}  // namespace rtc
