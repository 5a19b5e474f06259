// Appending strands to a Strands with the checks every loader needs: finite
// coordinates and radii, at least two points per strand. Centralised so that
// each loader only says *where* a bad value came from (line or byte offset).
#pragma once

#include "core/input_error.h"
#include "scenes/limits.h"
#include "scenes/scene.h"

#include <cmath>
#include <sstream>
#include <string>

namespace rtc {

namespace detail {
// A float as "1e+13" rather than std::to_string's "9999999827968.000000".
inline std::string shown(float x) {
    std::ostringstream os;
    os << x;
    return os.str();
}
}  // namespace detail

class StrandBuilder {
public:
    explicit StrandBuilder(Strands& out, std::string file) : out_(out), file_(std::move(file)) {}

    // `where` is e.g. "line 12" or "byte 4096"; only built when something fails.
    template <class Where>
    void add_point(const Vec3& p, float radius, Where&& where) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError(file_ + ": " + where() + ": non-finite coordinate in strand " +
                             std::to_string(out_.strand_count()));
        if (std::abs(p.x) > kMaxCoordinate || std::abs(p.y) > kMaxCoordinate ||
            std::abs(p.z) > kMaxCoordinate)
            throw InputError(file_ + ": " + where() + ": coordinate beyond +-" + kMaxCoordinateText + " in strand " +
                             std::to_string(out_.strand_count()));
        if (!std::isfinite(radius) || radius < 0.0f || radius > kMaxCoordinate)
            throw InputError(file_ + ": " + where() + ": bad radius " + detail::shown(radius) +
                             " in strand " + std::to_string(out_.strand_count()) + " (expected 0 to " +
                             kMaxCoordinateText + ")");
        out_.points.push_back(p);
        out_.radii.push_back(radius);
    }
    [[nodiscard]] std::size_t open_points() const { return out_.points.size() - out_.offsets.back(); }

    // Closes the current strand; fewer than two points is an error, never a
    // silent drop (a one-point strand means the file is not what we think).
    template <class Where>
    void end_strand(Where&& where) {
        if (open_points() < 2)
            throw InputError(file_ + ": " + where() + ": strand " +
                             std::to_string(out_.strand_count()) + " has " +
                             std::to_string(open_points()) + " point(s), need at least 2");
        out_.offsets.push_back(static_cast<std::uint32_t>(out_.points.size()));
    }

private:
    Strands& out_;
    std::string file_;
};

[[nodiscard]] inline auto at_byte(std::size_t offset) {
    return [offset] { return "byte " + std::to_string(offset); };
}
[[nodiscard]] inline auto at_line(std::size_t line) {
    return [line] { return "line " + std::to_string(line); };
}

}  // namespace rtc
