// Shared by the libFuzzer harnesses (tests/fuzz/README.md): the loaders read
// files, so each input is written to a per-process scratch file first
// (removed at exit). Any
// exception other than rtc::InputError escapes the harness, and libFuzzer
// reports it as a crash: bad input must always end as one clear InputError.
#pragma once

#include "core/input_error.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace rtc::fuzz {

// A small run config (tests/configs/tiny.json's shape) that the harnesses
// apply --set lines to.
inline constexpr const char* kTinyConfig = R"({
  "name": "tiny",
  "scene": {"type": "bundle", "count": 60, "radius": 0.01, "tilt_deg": 30, "seed": 2},
  "primitives": {"kind": "capsule"},
  "methods": ["ref", "obb"],
  "workload": {"type": "camera", "camera": "auto", "width": 8, "height": 8, "spp": 1, "bounces": 1}
})";

// Where scratch files go: /dev/shm (memory) when there is one, since
// rewriting a file on a virtual disk costs milliseconds, 10-100x the loader.
inline const std::string& scratch_dir() {
    static const std::string dir = [] {
        if (const char* d = std::getenv("RTCSIM_FUZZ_SCRATCH"); d && *d) return std::string(d);
        if (access("/dev/shm", W_OK) == 0) return std::string("/dev/shm");
        const char* tmp = std::getenv("TMPDIR");
        return std::string(tmp && *tmp ? tmp : "/tmp");
    }();
    return dir;
}

// A scratch file, unique per process and suffix, rewritten for every input.
inline std::string write_scratch(const std::uint8_t* data, std::size_t size, const char* suffix) {
    const std::string path = scratch_dir() + "/rtcsim_fuzz_" + std::to_string(getpid()) + suffix;
    static std::string remove_at_exit;  // one suffix per harness
    if (remove_at_exit.empty()) {
        remove_at_exit = path;
        std::atexit([] { std::remove(remove_at_exit.c_str()); });
    }
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path;
}

}  // namespace rtc::fuzz
