#include "core/box_test.h"

namespace rtc {

#if defined(__SSE2__)
const LaneConstants kLaneConstants = {{kSlabPad, kSlabPad, kSlabPad, kSlabPad},
                                      {kInfinity, kInfinity, kInfinity, kInfinity},
                                      {-0.0f, -0.0f, -0.0f, -0.0f}};
#endif

}  // namespace rtc
