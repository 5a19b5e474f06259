// Progress bar implementation (see progress.h).
#include "sim/util/progress.h"

#include "sim/util/table.h"

#include <algorithm>
#include <unistd.h>

namespace rtc {
namespace {

constexpr std::int64_t kRedrawIntervalNs = 100'000'000;  // 10 redraws per second at most
constexpr int kBarWidth = 30;

}  // namespace

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : Progress(std::move(label), total, enabled, stderr, isatty(fileno(stderr)) != 0) {}

Progress::Progress(std::string label, std::uint64_t total, bool enabled, std::FILE* out, bool is_tty)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled && out != nullptr),
      out_(out),
      tty_(is_tty),
      start_(std::chrono::steady_clock::now()) {
    if (!enabled_) return;
    std::lock_guard lock(draw_mutex_);
    if (tty_) draw_tty(0, false);
    else draw_plain(0, false);
}

Progress::~Progress() { finish(); }

double Progress::elapsed_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::advance(std::uint64_t n) {
    const std::uint64_t now_done = done_.fetch_add(n, std::memory_order_relaxed) + n;
    if (!enabled_) return;
    if (!tty_) {
        const int q = total_ ? static_cast<int>(std::min<std::uint64_t>(now_done * 4 / total_, 4)) : 0;
        int printed = quarters_printed_.load(std::memory_order_relaxed);
        // Quarters 1..3 here; 100% is finish()'s line.
        if (q > printed && q < 4 && quarters_printed_.compare_exchange_strong(printed, q)) {
            std::lock_guard lock(draw_mutex_);
            if (!finished_) draw_plain(now_done, false);
        }
        return;
    }
    const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::steady_clock::now() - start_).count();
    std::int64_t due = next_draw_ns_.load(std::memory_order_relaxed);
    if (now_ns < due) return;
    // Whoever moves the deadline forward draws; the others go back to work.
    if (!next_draw_ns_.compare_exchange_strong(due, now_ns + kRedrawIntervalNs)) return;
    std::unique_lock lock(draw_mutex_, std::try_to_lock);
    if (lock.owns_lock() && !finished_) draw_tty(done_.load(std::memory_order_relaxed), false);
}

void Progress::finish() {
    if (!enabled_) return;
    std::lock_guard lock(draw_mutex_);
    if (finished_) return;
    finished_ = true;
    const std::uint64_t d = done_.load(std::memory_order_relaxed);
    if (tty_) draw_tty(d, true);
    else draw_plain(d, true);
}

void Progress::draw_tty(std::uint64_t d, bool final) {
    const double frac = total_ ? std::min(1.0, static_cast<double>(d) / static_cast<double>(total_)) : (final ? 1.0 : 0.0);
    const int filled = static_cast<int>(frac * kBarWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(kBarWidth - filled), '.');
    std::string line = "\r" + label_;
    line += " [" + bar + "] ";
    line += format_fixed(frac * 100.0, 0) + "% ";
    line += format_thousands(static_cast<std::int64_t>(d)) + "/" + format_thousands(static_cast<std::int64_t>(total_));
    line += final ? " done in " : " ";
    line += format_duration(elapsed_seconds());
    line += final ? "\x1b[K\n" : "\x1b[K";  // erase what a longer previous line left behind
    std::fputs(line.c_str(), out_);
    std::fflush(out_);
}

void Progress::draw_plain(std::uint64_t d, bool final) {
    std::string line = label_ + ": ";
    if (final) {
        line += "done " + format_thousands(static_cast<std::int64_t>(d)) + " in " + format_duration(elapsed_seconds());
    } else if (d == 0) {
        line += "started (" + format_thousands(static_cast<std::int64_t>(total_)) + ")";
    } else {
        const double pct = total_ ? 100.0 * static_cast<double>(d) / static_cast<double>(total_) : 0.0;
        line += format_fixed(pct, 0) + "% (" + format_thousands(static_cast<std::int64_t>(d)) + "/" +
                format_thousands(static_cast<std::int64_t>(total_)) + ") " + format_duration(elapsed_seconds());
    }
    line += '\n';
    std::fputs(line.c_str(), out_);
    std::fflush(out_);
}

}  // namespace rtc
