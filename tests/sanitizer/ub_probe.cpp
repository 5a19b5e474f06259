// A planted UBSan report (issue 38, item 12): built only in the sanitizer
// builds (RTCSIM_SANITIZE, or RTCSIM_FUZZ: build-fuzz/, where scripts/test
// --ci runs the sanitized suite), run by two ctests (tests/CMakeLists.txt). It
// behaves like `simulate` given a rejected input, one line on stderr and
// exit 2, but first overflows a signed int when given "overflow". The
// end-to-end tests accept exit 2 with a message; a sanitizer report must
// fail them instead, so the leg's settings (-fno-sanitize-recover and
// UBSAN_OPTIONS=abort_on_error=1, scripts/test --ci) must turn the report
// into SIGABRT (exit status 134 in sh), not GCC's default exit 1 or a
// carry-on to exit 2.
#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv) {
    if (argc > 1 && std::strcmp(argv[1], "overflow") == 0) {
        // From the argument count, so the compiler cannot fold it away.
        volatile int big = 2147483600 + argc;
        const int sum = big + 100;  // signed overflow: undefined
        std::printf("sum %d\n", sum);
    }
    std::fprintf(stderr, "ub_probe: a rejected input\n");
    return 2;
}
