// Procedural hair (see hair_gen.h).
#include "scenes/generators/hair_gen.h"

#include "scenes/generators/random.h"
#include "scenes/generators/sphere_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rtc {

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

void check(const HairDesc& d) {
    if (d.strands == 0) throw std::invalid_argument("hair: strands must be at least 1");
    if (d.points_per_strand < 2) throw std::invalid_argument("hair: points_per_strand must be at least 2");
    if (!(d.length > 0.0f)) throw std::invalid_argument("hair: length must be positive");
    if (!(d.radius > 0.0f)) throw std::invalid_argument("hair: radius must be positive");
    if (d.emitter == HairEmitter::Sphere && !(d.sphere_radius > 0.0f))
        throw std::invalid_argument("hair: sphere radius must be positive");
    if (d.emitter == HairEmitter::Lock) {
        if (!(d.lock_radius > 0.0f)) throw std::invalid_argument("hair: lock radius must be positive");
        if (!(glm::length(d.lock_axis) > 0.0f)) throw std::invalid_argument("hair: lock axis must not be zero");
        if (d.with_mesh) throw std::invalid_argument("hair: a lock has no emitter mesh");
    }
    const std::uint64_t points = std::uint64_t{d.strands} * d.points_per_strand;
    if (points >= (std::uint64_t{1} << 32))
        throw std::invalid_argument("hair: " + std::to_string(points) + " points exceed 2^32");
}

// Any unit vector perpendicular to n, and a third completing the frame
// (Duff et al. 2017, branchless orthonormal basis).
void frame(const Vec3& n, Vec3& t1, Vec3& t2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    t1 = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t2 = Vec3(b, sign + n.y * n.y * a, -n.y);
}

// What a lock's strands share: the frame the curl is measured in and its phase.
struct SharedCurl {
    Vec3 t1;
    float phase;
};

// Grows one strand from `root` with unit normal `normal` into s; a strand of a
// lock takes its curl from `shared` (the lock's frame turned onto its axis).
void grow(const HairDesc& d, SceneRng& rng, const Vec3& root, const Vec3& normal, Strands& s,
          const SharedCurl* shared = nullptr) {
    Vec3 t1, t2;
    frame(normal, t1, t2);
    const float lean_angle = kTwoPi * static_cast<float>(rng.uniform());
    const float lean = d.lean * static_cast<float>(rng.uniform());
    const Vec3 axis = glm::normalize(normal + lean * (std::cos(lean_angle) * t1 + std::sin(lean_angle) * t2));
    if (shared) {
        t1 = glm::normalize(shared->t1 - glm::dot(shared->t1, axis) * axis);
        t2 = glm::cross(axis, t1);
    } else {
        frame(axis, t1, t2);
    }
    const float phase = shared ? shared->phase : kTwoPi * static_cast<float>(rng.uniform());
    const float tip = d.tip_radius < 0.0f ? d.radius : d.tip_radius;
    const std::uint32_t n = d.points_per_strand;
    // The centreline at u in [0, 1] (root to tip) and its derivative d/du.
    auto centre = [&](float u) {
        Vec3 p = root + (d.length * u) * axis;
        if (d.style == HairStyle::Wavy) {
            // Minus the value at u = 0, so the strand starts at its root.
            const float w = std::sin(kTwoPi * d.waves * u + phase) - std::sin(phase);
            p += (d.wave_amplitude * d.length * w) * t1;
        } else if (d.style == HairStyle::Curly) {
            const float a = kTwoPi * d.curl_turns * u + phase;
            p += (d.curl_radius * d.length) *
                 ((std::cos(a) - std::cos(phase)) * t1 + (std::sin(a) - std::sin(phase)) * t2);
        }
        return p;
    };
    auto tangent = [&](float u) {
        Vec3 v = d.length * axis;
        if (d.style == HairStyle::Wavy) {
            const float w = kTwoPi * d.waves;
            v += (d.wave_amplitude * d.length * w * std::cos(w * u + phase)) * t1;
        } else if (d.style == HairStyle::Curly) {
            const float w = kTwoPi * d.curl_turns, a = w * u + phase;
            v += (d.curl_radius * d.length * w) * (-std::sin(a) * t1 + std::cos(a) * t2);
        }
        return v;
    };
    auto at = [&](std::uint32_t k) { return static_cast<float>(k) / static_cast<float>(n - 1); };
    for (std::uint32_t k = 0; k < n; ++k) {
        const float u = at(k);
        const std::uint32_t first = k - k % 3;  // Bezier: the end point that opens k's curve
        if (d.basis == CurveBasis::Bezier && k % 3 != 0 && first + 3 <= n - 1) {
            // Hermite to Bezier over the curve's span h: the inner control
            // points leave each end along its tangent by h / 3.
            const float h = at(first + 3) - at(first);
            s.points.push_back(k % 3 == 1 ? centre(at(first)) + (h / 3.0f) * tangent(at(first))
                                          : centre(at(first + 3)) - (h / 3.0f) * tangent(at(first + 3)));
        } else {
            s.points.push_back(centre(u));
        }
        s.radii.push_back(d.radius + (tip - d.radius) * u);
    }
    s.offsets.push_back(static_cast<std::uint32_t>(s.points.size()));
}

void reserve(const HairDesc& d, Strands& s) {
    const std::size_t points = std::size_t{d.strands} * d.points_per_strand;
    s.points.reserve(points);
    s.radii.reserve(points);
    s.offsets.reserve(std::size_t{d.strands} + 1);
}

const char* style_name(HairStyle s) {
    return s == HairStyle::Straight ? "straight" : s == HairStyle::Wavy ? "wavy" : "curly";
}

}  // namespace

Scene make_hair(const HairDesc& d) {
    check(d);
    Scene scene;
    reserve(d, scene.strands);
    scene.strands.basis = d.basis;
    SceneRng rng(d.seed);
    if (d.emitter == HairEmitter::Lock) {
        scene.name = std::string("procedural ") + style_name(d.style) + " hair lock";
        // Roots uniform over the disk across the axis (square-root warp).
        const Vec3 axis = glm::normalize(d.lock_axis);
        Vec3 t1, t2;
        frame(axis, t1, t2);
        const SharedCurl shared{t1, kTwoPi * static_cast<float>(rng.uniform())};
        for (std::uint32_t i = 0; i < d.strands; ++i) {
            const float rho = d.lock_radius * std::sqrt(static_cast<float>(rng.uniform()));
            const float phi = kTwoPi * static_cast<float>(rng.uniform());
            const Vec3 root = d.lock_center + rho * (std::cos(phi) * t1 + std::sin(phi) * t2);
            grow(d, rng, root, axis, scene.strands, &shared);
        }
        return scene;
    }
    scene.name = std::string("procedural ") + style_name(d.style) + " hair on a sphere";
    for (std::uint32_t i = 0; i < d.strands; ++i) {
        // Uniform on the sphere: uniform height and azimuth (Archimedes).
        const float y = static_cast<float>(rng.uniform(-1.0, 1.0));
        const float phi = kTwoPi * static_cast<float>(rng.uniform());
        const float rho = std::sqrt(std::max(0.0f, 1.0f - y * y));
        const Vec3 normal(rho * std::cos(phi), y, rho * std::sin(phi));
        grow(d, rng, d.sphere_center + d.sphere_radius * normal, normal, scene.strands);
    }
    if (d.with_mesh) scene.mesh = make_sphere_mesh(d.sphere_center, d.sphere_radius);
    return scene;
}

Scene make_hair_on_mesh(const HairDesc& d, const TriangleMesh& emitter) {
    check(d);
    // Cumulative areas for area-weighted triangle choice.
    std::vector<double> cdf;
    cdf.reserve(emitter.triangles.size());
    double total = 0.0;
    std::size_t last_positive = 0;  // where a pick rounded up to `total` must land
    for (const auto& t : emitter.triangles) {
        const Vec3 &a = emitter.vertices.at(t[0]), &b = emitter.vertices.at(t[1]), &c = emitter.vertices.at(t[2]);
        // The same float cross product as below, so a triangle whose normal
        // cannot be formed has exactly zero weight and is never picked.
        total += 0.5 * static_cast<double>(glm::length(glm::cross(b - a, c - a)));
        if (total > (cdf.empty() ? 0.0 : cdf.back())) last_positive = cdf.size();
        cdf.push_back(total);
    }
    if (!(total > 0.0)) throw std::invalid_argument("hair: the emitter mesh has no area");
    Scene scene;
    scene.name = std::string("procedural ") + style_name(d.style) + " hair on a mesh";
    reserve(d, scene.strands);
    scene.strands.basis = d.basis;
    SceneRng rng(d.seed);
    for (std::uint32_t i = 0; i < d.strands; ++i) {
        const double pick = rng.uniform() * total;
        const std::size_t tri = std::min<std::size_t>(
            static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()),
            last_positive);
        const auto& t = emitter.triangles[tri];
        const Vec3 &a = emitter.vertices[t[0]], &b = emitter.vertices[t[1]], &c = emitter.vertices[t[2]];
        const Vec3 cross = glm::cross(b - a, c - a);
        // Uniform point in the triangle (square-root warp).
        const float su = std::sqrt(static_cast<float>(rng.uniform()));
        const float v = static_cast<float>(rng.uniform());
        const Vec3 root = (1.0f - su) * a + su * (1.0f - v) * b + su * v * c;
        grow(d, rng, root, glm::normalize(cross), scene.strands);
    }
    if (d.with_mesh) scene.mesh = emitter;
    return scene;
}

}  // namespace rtc
