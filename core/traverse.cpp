#include "core/traverse.h"

namespace rtc {

#if defined(__SSE2__)
const LaneConstants kLaneConstants = {{kSlabPad, kSlabPad, kSlabPad, kSlabPad},
                                      {kInfinity, kInfinity, kInfinity, kInfinity}};
#endif

}  // namespace rtc
