#include "sim/methods/common/cluster_moments.h"

#include <algorithm>
#include <cmath>

namespace rtc::cluster_detail {

std::array<DVec3, 3> eigenvectors(Sym3 a) {
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > 1e-30 * diag)) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                const double apq = a[p][q];
                if (apq == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                a[p][p] -= t * apq;
                a[q][q] += t * apq;
                a[p][q] = a[q][p] = 0.0;
                const int r = 3 - p - q;
                const double arp = a[r][p], arq = a[r][q];
                a[r][p] = a[p][r] = c * arp - s * arq;
                a[r][q] = a[q][r] = s * arp + c * arq;
                for (auto& row : v) {
                    const double vp = row[p], vq = row[q];
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    std::array<int, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
    std::array<DVec3, 3> out;
    for (int k = 0; k < 3; ++k) out[k] = DVec3(v[0][order[k]], v[1][order[k]], v[2][order[k]]);
    return out;
}

Axes complete(DVec3 x, const DVec3& hint) {
    const double lx = glm::length(x);
    x = lx > 0.0 && std::isfinite(lx) ? x / lx : DVec3(1, 0, 0);
    DVec3 y = hint - glm::dot(hint, x) * x;
    if (!(glm::length(y) > 1e-6)) {
        const DVec3 a = std::abs(x.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
        y = a - glm::dot(a, x) * x;
    }
    y = glm::normalize(y);
    return {x, y, glm::cross(x, y)};
}

DVec3 across(const Moments& m, const DVec3& x) {
    const Sym3 c = m.covariance();
    Sym3 p{}, pc{}, pcp{};
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) p[r][q] = (r == q ? 1.0 : 0.0) - x[r] * x[q];
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
            for (int s = 0; s < 3; ++s) pc[r][q] += p[r][s] * c[s][q];
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
            for (int s = 0; s < 3; ++s) pcp[r][q] += pc[r][s] * p[s][q];
    return eigenvectors(pcp)[0];
}

Axes principal_axes(const Moments& m) {
    const DVec3 x = glm::normalize(eigenvectors(m.orientation())[0]);
    return complete(x, across(m, x));
}

}  // namespace rtc::cluster_detail
