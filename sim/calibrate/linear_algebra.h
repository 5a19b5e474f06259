// The small dense linear algebra the calibrator needs (parameters x
// parameters matrices): a Cholesky solve and a symmetric eigen-decomposition.
#pragma once

#include <vector>

namespace rtc {

using Vec = std::vector<double>;
using Mat = std::vector<Vec>;  // row-major

// Solves A x = b for symmetric positive definite A (Cholesky); false if not SPD.
[[nodiscard]] bool solve_spd(Mat A, Vec b, Vec& x);

// Cyclic Jacobi eigen-decomposition of a small symmetric matrix: A = V diag(w) V^T,
// eigenvectors in the columns of V. Deterministic (fixed sweep order).
void eigen_symmetric(Mat A, Vec& w, Mat& V);

}  // namespace rtc
