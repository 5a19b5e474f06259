// `bench --compare A.json B.json`: before/after ratios of two `bench --json`
// files, matched by case, run and method.
#pragma once

#include <string>

namespace rtc {

// Prints, per method found in both files, B / A of the best rate at every
// thread count both timed and of the build time, and whether the event totals
// are identical. Returns the exit code: 0, or 1 when some totals differ.
// Throws InputError (naming the file) on unreadable or malformed files.
int compare_bench_json(const std::string& a_file, const std::string& b_file);

}  // namespace rtc
