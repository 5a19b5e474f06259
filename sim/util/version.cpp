#include "sim/util/version.h"

#include "rtcsim_git_stamp.h"  // generated at build time (cmake/git_stamp.cmake)

namespace rtc {

const char* git_commit() {
#ifdef RTCSIM_GIT_COMMIT
    return RTCSIM_GIT_COMMIT;
#else
    return "unknown";
#endif
}

bool git_dirty() {
#if defined(RTCSIM_GIT_DIRTY) && RTCSIM_GIT_DIRTY
    return true;
#else
    return false;
#endif
}

}  // namespace rtc
