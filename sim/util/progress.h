// Progress: a progress bar on stderr for the long phases ("build obb",
// "trace ref"). advance() is safe from worker threads: an atomic counter, and
// at most one thread redraws, at most ~10 times a second. On a terminal the
// bar redraws in place; otherwise (logs, CI) only a start line, one line per
// 25%, and the final line. Disabled (--quiet) it prints nothing at all.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace rtc {

class Progress {
public:
    // Writes to stderr, as a TTY if isatty(stderr).
    Progress(std::string label, std::uint64_t total, bool enabled);
    // Explicit stream and terminal mode, for tests and redirection.
    Progress(std::string label, std::uint64_t total, bool enabled, std::FILE* out, bool is_tty);
    ~Progress();  // calls finish() if it has not run

    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Thread-safe; cheap when no redraw is due (one atomic add, one clock read).
    void advance(std::uint64_t n = 1);
    // Prints the final line with the elapsed time; idempotent.
    void finish();

    [[nodiscard]] std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }
    [[nodiscard]] double elapsed_seconds() const;

private:
    void draw_tty(std::uint64_t done, bool final);
    void draw_plain(std::uint64_t done, bool final);

    std::string label_;
    std::uint64_t total_;
    bool enabled_;
    std::FILE* out_;
    bool tty_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<std::uint64_t> done_{0};
    std::atomic<std::int64_t> next_draw_ns_{0};  // since start_
    std::atomic<int> quarters_printed_{0};       // plain mode: 25% steps already reported
    std::mutex draw_mutex_;
    bool finished_ = false;  // guarded by draw_mutex_
};

}  // namespace rtc
