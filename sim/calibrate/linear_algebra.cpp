#include "sim/calibrate/linear_algebra.h"

#include <cmath>

namespace rtc {

// Solves A x = b for symmetric positive definite A (Cholesky); false if not SPD.
bool solve_spd(Mat A, Vec b, Vec& x) {
    const std::size_t n = b.size();
    for (std::size_t j = 0; j < n; ++j) {
        double d = A[j][j];
        for (std::size_t k = 0; k < j; ++k) d -= A[j][k] * A[j][k];
        if (!(d > 0.0)) return false;
        A[j][j] = std::sqrt(d);
        for (std::size_t i = j + 1; i < n; ++i) {
            double s = A[i][j];
            for (std::size_t k = 0; k < j; ++k) s -= A[i][k] * A[j][k];
            A[i][j] = s / A[j][j];
        }
    }
    for (std::size_t i = 0; i < n; ++i) {  // L y = b
        for (std::size_t k = 0; k < i; ++k) b[i] -= A[i][k] * b[k];
        b[i] /= A[i][i];
    }
    for (std::size_t i = n; i-- > 0;) {  // L^T x = y
        for (std::size_t k = i + 1; k < n; ++k) b[i] -= A[k][i] * b[k];
        b[i] /= A[i][i];
    }
    x = std::move(b);
    return true;
}

// Cyclic Jacobi eigen-decomposition of a small symmetric matrix: A = V diag(w) V^T,
// eigenvectors in the columns of V. Deterministic (fixed sweep order).
void eigen_symmetric(Mat A, Vec& w, Mat& V) {
    const std::size_t n = A.size();
    V.assign(n, Vec(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) V[i][i] = 1.0;
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0, diag = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            diag += A[i][i] * A[i][i];
            for (std::size_t j = i + 1; j < n; ++j) off += A[i][j] * A[i][j];
        }
        if (off <= 1e-30 * diag || off == 0.0) break;
        for (std::size_t p = 0; p < n; ++p)
            for (std::size_t q = p + 1; q < n; ++q) {
                if (A[p][q] == 0.0) continue;
                const double theta = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) /
                                 (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (std::size_t k = 0; k < n; ++k) {  // A <- A G (columns p, q)
                    const double akp = A[k][p], akq = A[k][q];
                    A[k][p] = c * akp - s * akq;
                    A[k][q] = s * akp + c * akq;
                }
                for (std::size_t k = 0; k < n; ++k) {  // A <- G^T A (rows p, q)
                    const double apk = A[p][k], aqk = A[q][k];
                    A[p][k] = c * apk - s * aqk;
                    A[q][k] = s * apk + c * aqk;
                }
                for (std::size_t k = 0; k < n; ++k) {
                    const double vkp = V[k][p], vkq = V[k][q];
                    V[k][p] = c * vkp - s * vkq;
                    V[k][q] = s * vkp + c * vkq;
                }
            }
    }
    w.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) w[i] = A[i][i];
}

}  // namespace rtc
