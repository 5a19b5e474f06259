// simulate's output directories: never mixed with what was there before.
//
// The rule: `simulate` writes only into a directory that is missing or empty,
// and marks it with a `.rtcsim-output` file. An existing non-empty directory
// is refused (exit 2) unless --force; --force then empties it, but only when
// it carries the mark, i.e. when everything in it came from an earlier run of
// simulate (sweep points, plots, reports); a non-empty directory without the
// mark (a home directory, a typo for the source tree) is refused even with
// --force. So stale sweep points and plots never survive a re-run, and
// nothing simulate did not write is deleted.
#pragma once

#include <string>

namespace rtc {

inline constexpr const char* kOutputMark = ".rtcsim-output";

// Makes `dir` ready for a run (see above) and checks it is writable. Throws
// InputError naming `dir`.
void prepare_output_dir(const std::string& dir, bool force);

// Creates `dir` (a sweep point's directory inside a prepared one).
void make_dir(const std::string& dir);

}  // namespace rtc
