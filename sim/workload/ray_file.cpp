// Ray and hit file reading and writing (formats in ray_file.h). Encoding is
// explicit little endian byte by byte, so files are portable whatever the
// host's byte order and whatever the layout of Ray.
#include "sim/workload/ray_file.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

namespace rtc {
namespace {

void store_u32(unsigned char* p, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint32_t load_u32(const unsigned char* p) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
    return v;
}
void store_f32(unsigned char* p, float f) { store_u32(p, std::bit_cast<std::uint32_t>(f)); }
float load_f32(const unsigned char* p) { return std::bit_cast<float>(load_u32(p)); }

std::string system_reason() { return errno ? std::string(" (") + std::strerror(errno) + ")" : ""; }

std::string fmt(float x) {
    std::ostringstream s;
    s << x;
    return s.str();
}
std::string fmt(const Vec3& v) {
    std::ostringstream s;
    s << '(' << v.x << ", " << v.y << ", " << v.z << ')';
    return s.str();
}

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Opens `path` for reading and returns its size in bytes, checking that it is
// a whole number of `record` byte records.
std::uint64_t open_records(std::ifstream& in, const std::string& path, std::size_t record,
                           const char* what) {
    require_regular_file(path);  // a directory "opens" with a size of 2^63-1
    errno = 0;
    in.open(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open " + what + system_reason());
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(0, std::ios::beg);
    if (end < 0 || !in) throw InputError(path + ": cannot determine the size of the " + what);
    const auto size = static_cast<std::uint64_t>(end);
    if (size % record != 0)
        throw InputError(path + ": size " + std::to_string(size) + " bytes is not a multiple of " +
                         std::to_string(record) + " (" + std::to_string(size % record) +
                         " trailing bytes at byte offset " +
                         std::to_string(size - size % record) + ")");
    return size / record;
}

void commit_once(std::unique_ptr<OutputFile>& out) {
    if (!out) return;
    std::unique_ptr<OutputFile> file = std::move(out);  // closed even when the commit throws
    file->commit();
}

// Decodes and validates one ray record at byte `offset` of `path`.
Ray decode_ray(const unsigned char* p, const std::string& path, std::uint64_t offset) {
    Ray r;
    r.origin = Vec3(load_f32(p), load_f32(p + 4), load_f32(p + 8));
    r.tmin = load_f32(p + 12);
    r.direction = Vec3(load_f32(p + 16), load_f32(p + 20), load_f32(p + 24));
    r.tmax = load_f32(p + 28);
    auto bad = [&](const std::string& problem) {
        throw InputError(path + ": byte offset " + std::to_string(offset) + " (ray " +
                         std::to_string(offset / kRayRecordBytes) + "): " + problem);
    };
    if (!finite(r.origin)) bad("origin is not finite " + fmt(r.origin));
    if (!finite(r.direction)) bad("direction is not finite " + fmt(r.direction));
    if (r.direction == Vec3(0.0f)) bad("direction is zero");
    if (!std::isfinite(r.tmin) || r.tmin < 0.0f)
        bad("tmin must be finite and >= 0, got " + fmt(r.tmin));
    if (std::isnan(r.tmax) || r.tmax < r.tmin)
        bad("tmax must be >= tmin (" + fmt(r.tmin) + "), got " + fmt(r.tmax));
    return r;
}

FileHit decode_hit(const unsigned char* p, const std::string& path, std::uint64_t offset) {
    const FileHit h{load_f32(p), load_u32(p + 4), static_cast<GeometryId>(load_u32(p + 8))};
    auto bad = [&](const std::string& problem) {
        throw InputError(path + ": byte offset " + std::to_string(offset) + " (hit " +
                         std::to_string(offset / kHitRecordBytes) + "): " + problem);
    };
    if (h.geom == GeometryId::None) {
        if (h.t != kInfinity || h.prim != kNoPrim)
            bad("a miss (geometry 0xFFFFFFFF) must have t = +inf and primitive 0xFFFFFFFF");
    } else {
        if (h.geom != GeometryId::Curves && h.geom != GeometryId::Triangles)
            bad("geometry id must be 0, 1 or 0xFFFFFFFF, got " +
                std::to_string(static_cast<std::uint32_t>(h.geom)));
        if (!std::isfinite(h.t) || h.t < 0.0f) bad("hit t must be finite and >= 0, got " + fmt(h.t));
        if (h.prim == kNoPrim) bad("a hit must name a primitive");
    }
    return h;
}

}  // namespace

// ---- rays ----------------------------------------------------------------

RayFileReader::RayFileReader(std::string path) : path_(std::move(path)) {
    count_ = open_records(in_, path_, kRayRecordBytes, "ray file");
}

std::size_t RayFileReader::read(std::span<Ray> out) {
    const auto n = static_cast<std::size_t>(
        std::min<std::uint64_t>(out.size(), count_ - next_));
    if (n == 0) return 0;
    if (buffer_.size() < n * kRayRecordBytes) buffer_.resize(n * kRayRecordBytes);
    in_.read(reinterpret_cast<char*>(buffer_.data()),
             static_cast<std::streamsize>(n * kRayRecordBytes));
    if (!in_)
        throw InputError(path_ + ": byte offset " + std::to_string(next_ * kRayRecordBytes) +
                         ": read failed (file changed while reading?)");
    for (std::size_t i = 0; i < n; ++i)
        out[i] = decode_ray(buffer_.data() + i * kRayRecordBytes, path_,
                            (next_ + i) * kRayRecordBytes);
    next_ += n;
    return n;
}

std::vector<Ray> read_ray_file(const std::string& path) {
    RayFileReader reader(path);
    std::vector<Ray> rays(static_cast<std::size_t>(reader.ray_count()));
    std::size_t done = 0;
    while (done < rays.size()) {
        const std::size_t chunk = std::min<std::size_t>(rays.size() - done, 1 << 16);
        done += reader.read(std::span<Ray>(rays).subspan(done, chunk));
    }
    return rays;
}

RayFileWriter::RayFileWriter(std::string path)
    : path_(std::move(path)), out_(std::make_unique<OutputFile>(path_)) {}

RayFileWriter::~RayFileWriter() = default;  // without close(): the partial file is removed

void RayFileWriter::append(std::span<const Ray> rays) {
    if (!out_) throw InputError(path_ + ": ray file already closed");
    if (buffer_.size() < rays.size() * kRayRecordBytes) buffer_.resize(rays.size() * kRayRecordBytes);
    unsigned char* p = buffer_.data();
    for (const Ray& r : rays) {
        const float v[8] = {r.origin.x,    r.origin.y,    r.origin.z,    r.tmin,
                            r.direction.x, r.direction.y, r.direction.z, r.tmax};
        for (float f : v) {
            store_f32(p, f);
            p += 4;
        }
    }
    out_->write(buffer_.data(), rays.size() * kRayRecordBytes);
    count_ += rays.size();
}

void RayFileWriter::close() { commit_once(out_); }

void write_ray_file(const std::string& path, std::span<const Ray> rays) {
    RayFileWriter w(path);
    w.append(rays);
    w.close();
}

// ---- hits ----------------------------------------------------------------

HitFileWriter::HitFileWriter(std::string path)
    : path_(std::move(path)), out_(std::make_unique<OutputFile>(path_)) {}

HitFileWriter::~HitFileWriter() = default;  // without close(): the partial file is removed

void HitFileWriter::append_one(const FileHit& h) {
    const std::size_t at = buffer_.size();
    buffer_.resize(at + kHitRecordBytes);
    store_f32(buffer_.data() + at, h.t);
    store_u32(buffer_.data() + at + 4, h.prim);
    store_u32(buffer_.data() + at + 8, static_cast<std::uint32_t>(h.geom));
}

void HitFileWriter::flush_buffer() {
    out_->write(buffer_.data(), buffer_.size());
    count_ += buffer_.size() / kHitRecordBytes;
    buffer_.clear();  // keeps the capacity
}

void HitFileWriter::append(std::span<const FileHit> hits) {
    if (!out_) throw InputError(path_ + ": hit file already closed");
    buffer_.reserve(hits.size() * kHitRecordBytes);
    for (const FileHit& h : hits) append_one(h);
    flush_buffer();
}

void HitFileWriter::append(std::span<const TraceHit> hits) {
    if (!out_) throw InputError(path_ + ": hit file already closed");
    buffer_.reserve(hits.size() * kHitRecordBytes);
    for (const TraceHit& h : hits) append_one(to_file_hit(h));
    flush_buffer();
}

void HitFileWriter::close() { commit_once(out_); }

void write_hit_file(const std::string& path, std::span<const FileHit> hits) {
    HitFileWriter w(path);
    w.append(hits);
    w.close();
}

std::vector<FileHit> read_hit_file(const std::string& path) {
    std::ifstream in;
    const std::uint64_t count = open_records(in, path, kHitRecordBytes, "hit file");
    std::vector<unsigned char> bytes(static_cast<std::size_t>(count * kHitRecordBytes));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!in) throw InputError(path + ": read failed");
    std::vector<FileHit> hits(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < hits.size(); ++i)
        hits[i] = decode_hit(bytes.data() + i * kHitRecordBytes, path, i * kHitRecordBytes);
    return hits;
}

}  // namespace rtc
