// LD_PRELOAD shim for simulate_lock_unsupported: flock() fails as on a file
// system without locks (some network and FUSE file systems), so the test
// sees what simulate says there (sim/app/output_dir.h).
#include <cerrno>

extern "C" int flock(int, int) {
    errno = ENOSYS;
    return -1;
}
