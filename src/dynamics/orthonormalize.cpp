#include <Eigen/SVD>
#include <algorithm>

#include "lagrange/dynamics.hpp"
#include "lagrange/rigid_body.hpp"

namespace lagrange {

// docs/theory.md §4.4: the nearest rotation to R in the Frobenius norm is the orthogonal polar
// factor U Vᵀ of R = U Σ Vᵀ (det U Vᵀ = +1 near SO(3), where R drifts from). Ξ only makes
// RᵀR − 1 decay; this removes what the integrator's error leaves, as the constraint
// projection does for C.
double orthonormalize_rotations(const CompiledModel& model, double* q, double tol) {
  double largest = 0.0;
  for (const size_t offset : model.rotations) {
    double* R = q + offset;
    const double error = orthonormality_error(R);
    largest = std::max(largest, error);
    if (!(error > tol)) continue;
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> Rm(R);
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(Rm, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU();
    if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) = -U.col(2);
    Rm = U * svd.matrixV().transpose();
  }
  return largest;
}

}  // namespace lagrange
