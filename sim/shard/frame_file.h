// A shard's traced frame on disk: what one band of one method's frame
// produced (totals of each task, the pixels it wrote, rays and hits when
// recorded), in a little-endian binary file that only this build reads back
// (the merge refuses files of another version; docs/scale-out.md).
#pragma once

#include "sim/execution/frame.h"

#include <functional>
#include <string>

namespace rtc {

void write_frame_file(const std::string& path, const FrameResult& frame);

// The per-item arrays (pixels, or rays of a ray list) hold only the band's
// items [item_begin, item_end), and the totals only per task (`tasks`).
// Throws InputError "<path>: byte N: ..." on a truncated, foreign or
// inconsistent file, with every count checked against the file size before
// anything is allocated.
[[nodiscard]] FrameResult read_frame_file(const std::string& path);

// Adds the bands of one frame (in band order, each from read_frame_file or a
// banded run) into the frame a single run would have made: pixels from the
// band that wrote them, totals summed task by task in task order (so the
// floating-point warp totals are bit-identical), rays and hits in order.
// Throws InputError naming `what` when the bands do not tile the frame.
// `band_at(i)` gives band i (0 .. count - 1) as read_frame_file returns it;
// one band is held at a time. The first band must start at item 0 and each
// next one where the previous ended, so the whole frame's arrays never grow
// past the items the files hold (camera frames: width x height, which the
// caller checks against the config before merging).
[[nodiscard]] FrameResult merge_frame_bands(std::size_t count, const std::function<FrameResult(std::size_t)>& band_at,
                                            const std::string& what);

}  // namespace rtc
