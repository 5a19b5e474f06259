#include "core/parallel.h"

namespace rtc {

unsigned hardware_threads() {
    // hardware_concurrency() may report 0 when it cannot tell.
    return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace rtc
