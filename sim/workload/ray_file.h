// Binary ray files (input workloads) and hit files (results), so that a fixed
// set of rays can be traced by every method and the hits compared offline.
//
// Ray file: 32 bytes per ray, little endian, eight float32
//   ox oy oz tmin dx dy dz tmax
// with t in units of |d| (d need not be normalized); tmax may be +inf.
// Reading validates every ray (finite origin and direction, non-zero
// direction, 0 <= tmin <= tmax, tmax not NaN) and names the file and the byte
// offset of the first bad ray.
//
// Hit file: 12 bytes per ray, little endian
//   float32 t (+inf on a miss), uint32 primitive index (0xFFFFFFFF on a miss),
//   uint32 geometry id (0 curves, 1 triangles, 0xFFFFFFFF miss).
#pragma once

#include "core/ray.h"
#include "sim/hardware/trace_hit.h"
#include "sim/util/json_file.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace rtc {

inline constexpr std::size_t kRayRecordBytes = 32;
inline constexpr std::size_t kHitRecordBytes = 12;
inline constexpr std::uint32_t kNoPrim = 0xFFFFFFFFu;

// Sequential reader: opens the file and checks its size once, then hands out
// validated rays in caller-sized batches (no allocation per ray).
class RayFileReader {
public:
    explicit RayFileReader(std::string path);  // throws InputError
    [[nodiscard]] std::uint64_t ray_count() const { return count_; }
    [[nodiscard]] std::uint64_t rays_read() const { return next_; }
    // Fills the front of `out`; returns how many rays were read, 0 at the end.
    [[nodiscard]] std::size_t read(std::span<Ray> out);

private:
    std::string path_;
    std::ifstream in_;
    std::uint64_t count_ = 0;
    std::uint64_t next_ = 0;
    std::vector<unsigned char> buffer_;
};

// Reads and validates a whole ray file.
[[nodiscard]] std::vector<Ray> read_ray_file(const std::string& path);

// Streaming writer: append batches, then close(). The file is written under
// a temporary name (OutputFile) and renamed to `path` by close(): destroyed
// without close() (a failed or interrupted run) it leaves nothing, so a cut
// file is never found under the real name and replayed as a whole one.
// Errors are InputErrors naming the path.
class RayFileWriter {
public:
    explicit RayFileWriter(std::string path);
    RayFileWriter(const RayFileWriter&) = delete;
    RayFileWriter& operator=(const RayFileWriter&) = delete;
    ~RayFileWriter();
    void append(std::span<const Ray> rays);
    void close();
    [[nodiscard]] std::uint64_t rays_written() const { return count_; }

private:
    std::string path_;
    std::unique_ptr<OutputFile> out_;  // null once closed
    std::uint64_t count_ = 0;
    std::vector<unsigned char> buffer_;
};

void write_ray_file(const std::string& path, std::span<const Ray> rays);

// What a hit file stores of one ray's closest hit.
struct FileHit {
    float t = kInfinity;
    std::uint32_t prim = kNoPrim;
    GeometryId geom = GeometryId::None;

    [[nodiscard]] bool hit() const { return geom != GeometryId::None; }
    friend bool operator==(const FileHit&, const FileHit&) = default;
};

// A miss maps to (+inf, 0xFFFFFFFF, None) whatever else the TraceHit holds.
[[nodiscard]] inline FileHit to_file_hit(const TraceHit& h) {
    if (!h.hit()) return {};
    return {h.t, h.prim, h.geom};
}

// As RayFileWriter: nothing under `path` unless close() was called.
class HitFileWriter {
public:
    explicit HitFileWriter(std::string path);
    HitFileWriter(const HitFileWriter&) = delete;
    HitFileWriter& operator=(const HitFileWriter&) = delete;
    ~HitFileWriter();
    void append(std::span<const FileHit> hits);
    void append(std::span<const TraceHit> hits);
    void close();
    [[nodiscard]] std::uint64_t hits_written() const { return count_; }

private:
    void append_one(const FileHit& h);
    void flush_buffer();
    std::string path_;
    std::unique_ptr<OutputFile> out_;  // null once closed
    std::uint64_t count_ = 0;
    std::vector<unsigned char> buffer_;
};

void write_hit_file(const std::string& path, std::span<const FileHit> hits);

// Reads a whole hit file; validates that each record is either a miss
// (+inf, 0xFFFFFFFF, 0xFFFFFFFF) or a hit (t >= 0 finite, geometry 0 or 1,
// primitive != 0xFFFFFFFF), naming the file and byte offset otherwise.
[[nodiscard]] std::vector<FileHit> read_hit_file(const std::string& path);

}  // namespace rtc
