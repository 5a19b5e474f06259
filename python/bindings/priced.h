// A priced run as Python sees it: the per-event pricing, and under a warp
// preset the warp model's figures too.
#pragma once

#include "sim/hardware/cost_model.h"
#include "sim/hardware/warp_pricing.h"

#include <optional>

namespace rtc::py_bind {

struct Priced {
    PricedRun run;
    std::optional<WarpTotals> warp;  // warp presets: the waves' figures
    int warp_width = 32;
    Roofline roof;                   // the SM they were priced on (sm_model.h)
};

}  // namespace rtc::py_bind
