// A shard's traced frame on disk: what one band of one method's frame
// produced (totals of each task, the pixels it wrote, rays and hits when
// recorded), in a little-endian binary file that only this build reads back
// (the merge refuses files of another version; docs/scale-out.md).
#pragma once

#include "sim/execution/frame.h"

#include <functional>
#include <string>

namespace rtc {

// What a frame file is a band of: the run (a hash of the sweep point's
// effective config), the method and the band, as one line of text recorded in
// the file; the merge computes the identity it expects from the config it
// plans and refuses a file with another (swapped methods, a band of a run
// with another seed, a shard.json whose config was edited).
[[nodiscard]] std::string frame_identity(const std::string& effective_config, const std::string& method,
                                         std::size_t point, std::uint32_t band, std::uint32_t bands);
// FNV-1a (64 bits) of `text`, in hex: the config hash of frame_identity and shard.json.
[[nodiscard]] std::string config_hash(const std::string& text);
// The same of a file's bytes, read in blocks; throws InputError naming `path`
// when it cannot be read (shard.json's input hashes).
[[nodiscard]] std::string file_hash(const std::string& path);

void write_frame_file(const std::string& path, const FrameResult& frame, const std::string& identity);

// The per-item arrays (pixels, or rays of a ray list) hold only the band's
// items [item_begin, item_end), and the totals only per task (`tasks`).
// Throws InputError "<path>: byte N: ..." on a truncated, foreign, misplaced or
// inconsistent file, with every count checked against the file size before
// anything is allocated.
// A file whose identity is not `identity` is refused, naming both, and so is a
// frame of another shape than `expected` (the config's), as soon as the header
// says so: the merge allocates the whole frame, so the file must not size it.
struct FrameShape {
    int width = 0, height = 0;  // 0 x 0: a ray list
};
[[nodiscard]] FrameResult read_frame_file(const std::string& path, const std::string& identity,
                                          const FrameShape& expected);

// Adds the bands of one frame (in band order, each from read_frame_file or a
// banded run) into the frame a single run would have made: pixels from the
// band that wrote them, totals summed task by task in task order (so the
// floating-point warp totals are bit-identical), rays and hits in order.
// Throws InputError naming `what` when the bands do not tile the frame.
// `band_at(i)` gives band i (0 .. count - 1) as read_frame_file returns it;
// one band is held at a time. The first band must start at item 0 and each
// next one where the previous ended, so the whole frame's arrays never grow
// past the items the files hold (camera frames: width x height, which
// read_frame_file has checked against the config's FrameShape).
[[nodiscard]] FrameResult merge_frame_bands(std::size_t count, const std::function<FrameResult(std::size_t)>& band_at,
                                            const std::string& what);

}  // namespace rtc
