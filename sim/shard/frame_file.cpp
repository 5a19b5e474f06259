#include "sim/shard/frame_file.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"
#include "sim/util/json_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <string_view>
#include <vector>
#include <type_traits>

namespace rtc {

namespace {

constexpr char kMagic[8] = {'R', 'T', 'C', 'F', 'R', 'A', 'M', 'E'};
constexpr std::uint32_t kFormat = 3;  // 2: the identity after the event count; 3: warp results by preset name
constexpr std::uint32_t kMaxIdentity = 4096;
constexpr std::uint32_t kMaxPresetName = 4096;
constexpr std::uint32_t kMaxDraws = 1u << 16;

// Bands of one run price the same presets, by name, with as many draws.
bool same_presets(const std::vector<PresetWarp>& a, const std::vector<PresetWarp>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t p = 0; p < a.size(); ++p)
        if (a[p].preset != b[p].preset || a[p].draws.size() != b[p].draws.size()) return false;
    return true;
}

class Writer {
public:
    explicit Writer(const std::string& path) : file_(path) {}

    void bytes(const void* p, std::size_t n) { file_.write(p, n); }
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes(&v, sizeof v);
    }
    template <class T, class Alloc>
    void array(const std::vector<T, Alloc>& v, std::size_t begin, std::size_t end) {
        static_assert(std::is_trivially_copyable_v<T>);
        put<std::uint64_t>(end - begin);
        if (end > begin) bytes(v.data() + begin, (end - begin) * sizeof(T));
    }
    void close() { file_.commit(); }

private:
    OutputFile file_;  // under a temporary name until close()
};

class Reader {
public:
    explicit Reader(const std::string& path) : in_(read_file_bytes(path), path) {}

    template <class T>
    T get(const char* what) {
        const T v = in_.get<T>(at_, what);
        at_ += sizeof(T);
        return v;
    }
    // A counted array of `T`, checked against the bytes left before allocating.
    template <class T>
    std::vector<T> array(const std::string& what) {
        const std::size_t count_at = at_;
        const auto n = get<std::uint64_t>(what.c_str());
        in_.require_records(at_, n, sizeof(T), what, count_at);
        std::vector<T> v(static_cast<std::size_t>(n));
        if (n) std::memcpy(v.data(), in_.data(at_), v.size() * sizeof(T));
        at_ += v.size() * sizeof(T);
        return v;
    }
    // Throws unless `n` records of `bytes` each fit in what is left.
    void require_records(std::uint64_t n, std::size_t bytes, const std::string& what, std::size_t count_at) const {
        in_.require_records(at_, n, bytes, what, count_at);
    }
    [[noreturn]] void fail(const std::string& problem) const { in_.fail(at_, problem); }
    [[noreturn]] void fail_at(std::size_t at, const std::string& problem) const { in_.fail(at, problem); }
    [[nodiscard]] std::size_t offset() const { return at_; }
    [[nodiscard]] bool at_end() const { return at_ == in_.size(); }

private:
    ByteReader in_;
    std::size_t at_ = 0;
};

}  // namespace

namespace {

constexpr std::uint64_t kFnvBasis = 0xcbf29ce484222325ull;

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h) {
    for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
    return h;
}

std::string hex_of(std::uint64_t h) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

}  // namespace

std::string config_hash(const std::string& text) { return hex_of(fnv1a(text, kFnvBasis)); }

std::string file_hash(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file (" + std::strerror(errno) + ")");
    std::vector<char> block(1 << 20);
    std::uint64_t h = kFnvBasis;
    while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        h = fnv1a(std::string_view(block.data(), static_cast<std::size_t>(in.gcount())), h);
    }
    if (in.bad()) throw InputError(path + ": read failed");
    return hex_of(h);
}

std::string frame_identity(const std::string& effective_config, const std::string& method, std::size_t point,
                           std::uint32_t band, std::uint32_t bands) {
    return "config " + config_hash(effective_config) + ", method " + method + ", point " + std::to_string(point) +
           ", band " + std::to_string(band) + " of " + std::to_string(bands);
}

void write_frame_file(const std::string& path, const FrameResult& f, const std::string& identity) {
    if (identity.size() > kMaxIdentity) throw InputError(path + ": internal: identity too long");
    Writer w(path);
    w.bytes(kMagic, sizeof kMagic);
    w.put(kFormat);
    w.put(static_cast<std::uint32_t>(kEventCount));
    w.put(static_cast<std::uint32_t>(identity.size()));
    w.bytes(identity.data(), identity.size());
    // The warp presets: each one's name and number of draws.
    w.put(static_cast<std::uint32_t>(f.warp.size()));
    for (const PresetWarp& p : f.warp) {
        if (p.preset.size() > kMaxPresetName) throw InputError(path + ": internal: preset name too long");
        w.put(static_cast<std::uint32_t>(p.preset.size()));
        w.bytes(p.preset.data(), p.preset.size());
        w.put(static_cast<std::uint32_t>(p.draws.size()));
    }
    w.put(static_cast<std::int32_t>(f.width));
    w.put(static_cast<std::int32_t>(f.height));
    w.put(static_cast<std::uint64_t>(f.task_count));
    w.put(static_cast<std::uint64_t>(f.task_begin));
    w.put(static_cast<std::uint64_t>(f.item_begin));
    w.put(f.trace_seconds);
    w.put(static_cast<std::uint64_t>(f.tasks.size()));
    for (const FrameTask& t : f.tasks) {
        if (t.warp.size() != f.warp.size()) throw InputError(path + ": internal: a task's warp presets differ");
        w.put(t.totals);
        w.put(t.rays_traced);
        for (std::size_t p = 0; p < t.warp.size(); ++p) {
            if (t.warp[p].draws.size() != f.warp[p].draws.size())
                throw InputError(path + ": internal: a task's draws differ");
            w.put(t.warp[p].totals);
            for (const WarpTotals& x : t.warp[p].draws) w.put(x);
        }
    }
    // The band's slice of each per-item array (empty arrays stay empty).
    const auto slice = [&](const auto& v) { w.array(v, v.empty() ? 0 : f.item_begin, v.empty() ? 0 : f.item_end); };
    slice(f.pixel_counts);
    slice(f.ray_counts);
    slice(f.radiance);
    for (const PresetWarp& p : f.warp) slice(p.pixel_cycles);
    slice(f.pixel_simt_active);
    slice(f.pixel_simt_slots);
    w.array(f.rays, 0, f.rays.size());
    w.array(f.hits, 0, f.hits.size());
    w.close();
}

FrameResult read_frame_file(const std::string& path, const std::string& identity, const FrameShape& expected) {
    Reader r(path);
    char magic[8];
    for (char& c : magic) c = r.get<char>("header");
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("not an rtcsim shard frame file");
    if (r.get<std::uint32_t>("format") != kFormat) r.fail("frame file format of another rtcsim version");
    if (r.get<std::uint32_t>("event count") != kEventCount)
        r.fail("written by an rtcsim with other events (another version)");
    const std::size_t identity_at = r.offset();
    const auto length = r.get<std::uint32_t>("identity length");
    if (length > kMaxIdentity) r.fail("implausible identity length " + std::to_string(length));
    r.require_records(length, 1, "identity", identity_at);
    std::string found(length, '\0');
    for (char& c : found) c = r.get<char>("identity");
    if (found != identity) r.fail("a frame of " + found + "; the merge expects " + identity);
    const auto presets = r.get<std::uint32_t>("warp presets");
    if (presets > 1024) r.fail("implausible warp preset count " + std::to_string(presets));
    FrameResult f;
    f.warp.resize(presets);  // names and draw counts; the totals are the tasks'
    std::uint64_t priced = 0;  // per task: every preset's totals and draws
    for (PresetWarp& p : f.warp) {
        const std::size_t name_at = r.offset();
        const auto length = r.get<std::uint32_t>("preset name length");
        if (length == 0 || length > kMaxPresetName) r.fail("implausible preset name length " + std::to_string(length));
        r.require_records(length, 1, "preset name", name_at);
        p.preset.resize(length);
        for (char& c : p.preset) c = r.get<char>("preset name");
        const auto draws = r.get<std::uint32_t>("preset draws");
        if (draws > kMaxDraws) r.fail("implausible draw count " + std::to_string(draws));
        p.draws.resize(draws);
        priced += 1 + draws;
    }
    const std::size_t shape_at = r.offset();
    f.width = r.get<std::int32_t>("width");
    f.height = r.get<std::int32_t>("height");
    if (f.width < 0 || f.height < 0 || (f.width == 0) != (f.height == 0)) r.fail("bad frame size");
    if (f.width != expected.width || f.height != expected.height) {
        const auto shape = [](int w, int h) {
            return w ? std::to_string(w) + " x " + std::to_string(h) + " frame" : std::string("ray list");
        };
        r.fail_at(shape_at, "a " + shape(f.width, f.height) + ", the config's is a " +
                                shape(expected.width, expected.height));
    }
    f.task_count = r.get<std::uint64_t>("task count");
    f.task_begin = r.get<std::uint64_t>("first task");
    f.item_begin = r.get<std::uint64_t>("first item");
    f.trace_seconds = r.get<double>("trace seconds");
    const std::size_t tasks_at = r.offset();
    const auto tasks = r.get<std::uint64_t>("tasks");
    if (tasks > f.task_count || f.task_begin > f.task_count - tasks) {
        r.fail("tasks " + std::to_string(f.task_begin) + " + " + std::to_string(tasks) + " exceed the frame's " +
               std::to_string(f.task_count));
    }
    r.require_records(tasks, sizeof(EventTotals) + sizeof(std::uint64_t) + priced * sizeof(WarpTotals), "tasks",
                      tasks_at);
    f.tasks.resize(static_cast<std::size_t>(tasks));
    for (FrameTask& t : f.tasks) {
        t.totals = r.get<EventTotals>("task totals");
        t.rays_traced = r.get<std::uint64_t>("task rays");
        t.warp.resize(presets);
        for (std::size_t p = 0; p < presets; ++p) {
            t.warp[p].totals = r.get<WarpTotals>("task warp totals");
            t.warp[p].draws.resize(f.warp[p].draws.size());
            for (WarpTotals& x : t.warp[p].draws) x = r.get<WarpTotals>("task draw totals");
        }
    }
    f.task_end = f.task_begin + f.tasks.size();
    // Items are pixels (camera frames) or rays (ray lists). Arrays keep only
    // the band's items (nothing is allocated beyond what the file holds); a
    // camera band must lie inside its frame.
    const std::size_t pixels = static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height);
    const auto slice = [&](auto& band, auto part, const char* what) {
        if (part.empty()) return;
        if (pixels && (f.item_begin > pixels || part.size() > pixels - f.item_begin))
            r.fail(std::string(what) + " outside the " + std::to_string(pixels) + "-pixel frame");
        if (f.item_end != f.item_begin && f.item_end != f.item_begin + part.size())
            r.fail(std::string(what) + ": " + std::to_string(part.size()) + " items, the band has " +
                   std::to_string(f.item_end - f.item_begin));
        f.item_end = f.item_begin + part.size();
        band.assign(part.begin(), part.end());
    };
    f.item_end = f.item_begin;
    slice(f.pixel_counts, r.array<RayCounts>("pixel counts"), "pixel counts");
    slice(f.ray_counts, r.array<RayCounts>("ray counts"), "ray counts");
    slice(f.radiance, r.array<Vec3>("radiance"), "radiance");
    for (PresetWarp& p : f.warp) slice(p.pixel_cycles, r.array<float>("pixel warp cycles"), "pixel warp cycles");
    slice(f.pixel_simt_active, r.array<float>("pixel SIMT lanes"), "pixel SIMT lanes");
    slice(f.pixel_simt_slots, r.array<float>("pixel SIMT slots"), "pixel SIMT slots");
    f.rays = r.array<Ray>("rays");
    f.hits = r.array<TraceHit>("hits");
    if (!r.at_end()) r.fail("unexpected bytes after the hits");
    return f;  // totals stay per task: merge_frame_bands adds them in order
}

FrameResult merge_frame_bands(std::size_t count, const std::function<FrameResult(std::size_t)>& band_at,
                              const std::string& what) {
    if (count == 0) throw InputError(what + ": no bands to merge");
    FrameResult out;
    std::size_t next_task = 0;
    // Copies a band's items (its array holds items [b, b + part.size())) into
    // the whole frame's array of `items`.
    const auto take = [](auto& full, const auto& part, std::size_t b, std::size_t items) {
        if (part.empty()) return;
        using T = typename std::decay_t<decltype(full)>::value_type;
        if (full.size() < items) full.resize(items, T{});  // zeros where no band has items
        std::copy(part.begin(), part.end(), full.begin() + static_cast<std::ptrdiff_t>(b));
    };
    for (std::size_t i = 0; i < count; ++i) {
        const FrameResult b = band_at(i);  // one band in memory at a time
        const std::string band = what + ": band " + std::to_string(i);
        if (i == 0) {
            out.width = b.width;
            out.height = b.height;
            out.task_count = b.task_count;
            for (const PresetWarp& p : b.warp) {  // names and draw counts; totals added below
                out.warp.emplace_back();
                out.warp.back().preset = p.preset;
                out.warp.back().draws.resize(p.draws.size());
            }
        } else if (b.width != out.width || b.height != out.height || b.task_count != out.task_count ||
                   !same_presets(b.warp, out.warp)) {
            throw InputError(band + ": frame shape or warp presets differ from band 0's (shards of different runs?)");
        }
        if (b.task_begin != next_task)
            throw InputError(band + ": starts at task " + std::to_string(b.task_begin) + ", expected " +
                             std::to_string(next_task) + " (a band is missing or repeated)");
        next_task = b.task_begin + b.tasks.size();
        for (const FrameTask& t : b.tasks) {  // the single run's order: task 0, 1, 2, ...
            if (t.warp.size() != out.warp.size()) throw InputError(band + ": a task's warp presets differ");
            out.totals += t.totals;
            out.rays_traced += t.rays_traced;
            for (std::size_t p = 0; p < out.warp.size(); ++p) out.warp[p] += t.warp[p];
        }
        // Items: pixels of the frame, or rays of the list (up to this band's end).
        const std::size_t items = out.width ? static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height)
                                            : b.item_end;
        if (b.item_begin > b.item_end || b.item_end > items || b.item_begin != out.item_end)
            throw InputError(band + ": items " + std::to_string(b.item_begin) + " .. " + std::to_string(b.item_end) +
                             " do not follow the previous band's " + std::to_string(out.item_end));
        const auto take_all = [&](auto& full, const auto& part) {
            if (!part.empty() && part.size() != b.item_end - b.item_begin)
                throw InputError(band + ": an array does not hold its band's items");
            take(full, part, b.item_begin, items);
        };
        take_all(out.pixel_counts, b.pixel_counts);
        take_all(out.ray_counts, b.ray_counts);
        take_all(out.radiance, b.radiance);
        for (std::size_t p = 0; p < out.warp.size(); ++p) take_all(out.warp[p].pixel_cycles, b.warp[p].pixel_cycles);
        take_all(out.pixel_simt_active, b.pixel_simt_active);
        take_all(out.pixel_simt_slots, b.pixel_simt_slots);
        out.item_end = b.item_end;
        out.rays.insert(out.rays.end(), b.rays.begin(), b.rays.end());
        out.hits.insert(out.hits.end(), b.hits.begin(), b.hits.end());
        out.trace_seconds += b.trace_seconds;
    }
    if (next_task != out.task_count)
        throw InputError(what + ": the bands cover tasks 0 .. " + std::to_string(next_task) + " of " +
                         std::to_string(out.task_count) + " (a band is missing)");
    out.task_end = out.task_count;
    return out;
}

}  // namespace rtc
