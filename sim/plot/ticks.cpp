// Nice tick placement (see ticks.h).
#include "sim/plot/ticks.h"

#include "sim/util/table.h"

#include <algorithm>
#include <cmath>

namespace rtc {
namespace {

double nice_step(double span, int target) {
    const double raw = span / std::max(target, 1);
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * mag >= raw * (1.0 - 1e-9)) return m * mag;
    return 10.0 * mag;
}

}  // namespace

std::string format_tick(double value, double step) {
    if (std::abs(value) < std::abs(step) * 1e-9) value = 0.0;  // no "-0"
    double scale = 1.0;
    const char* suffix = "";
    const double a = std::max(std::abs(value), std::abs(step));
    if (a >= 1e9) scale = 1e9, suffix = "G";
    else if (a >= 1e6) scale = 1e6, suffix = "M";
    else if (a >= 1e4) scale = 1e3, suffix = "k";
    const double s = std::abs(step) / scale;
    const int decimals = s > 0.0 ? std::clamp(static_cast<int>(-std::floor(std::log10(s) + 1e-9)), 0, 12) : 0;
    return format_fixed(value / scale, decimals) + suffix;
}

std::vector<Tick> linear_ticks(double lo, double hi, int target) {
    std::vector<Tick> ticks;
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) return ticks;
    if (lo == hi) {
        ticks.push_back({lo, format_sig(lo, 3)});
        return ticks;
    }
    const double step = nice_step(hi - lo, target);
    const double first = std::ceil(lo / step - 1e-9);
    for (double k = first;; k += 1.0) {
        const double v = k * step;
        if (v > hi + step * 1e-9) break;
        ticks.push_back({v, format_tick(v, step)});
    }
    return ticks;
}

std::vector<Tick> log_ticks(double lo, double hi) {
    std::vector<Tick> ticks;
    if (!(lo > 0.0) || !std::isfinite(hi) || lo > hi) return ticks;
    const double tol = 1e-9;
    const int d0 = static_cast<int>(std::ceil(std::log10(lo) - tol));
    const int d1 = static_cast<int>(std::floor(std::log10(hi) + tol));
    const int decades = d1 - d0 + 1;
    if (decades >= 3) {
        const int stride = (decades + 7) / 8;  // at most ~8 labels
        for (int d = d0; d <= d1; d += stride) {
            const double v = std::pow(10.0, d);
            ticks.push_back({v, format_sig(v, 1)});
        }
        return ticks;
    }
    for (int d = d0 - 1; d <= d1; ++d)
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, d);
            if (v >= lo * (1 - tol) && v <= hi * (1 + tol)) ticks.push_back({v, format_sig(v, 1)});
        }
    if (ticks.size() < 2) return linear_ticks(lo, hi, 4);
    return ticks;
}

}  // namespace rtc
