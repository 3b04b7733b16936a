#pragma once
// Sparse KKT solve for a diagonal mass matrix (e.g. chains in Cartesian coordinates).

#include <Eigen/Dense>
#include <vector>

#include "dynamics/envelope_cholesky.hpp"
#include "lagrange/compiled_model.hpp"

namespace lagrange::dynamics {

/// Range-space KKT solve when M is diagonal (docs/theory.md §4.3):
///   S = G M⁻¹ Gᵀ (sparse, pattern fixed at construction), S λ = G M⁻¹(h + Q) − γ,
///   a = M⁻¹(h + Q − Gᵀ λ).
/// S is factorised by an envelope Cholesky in the constraints' natural order, so the cost per
/// call is linear in the number of constraints for banded G (chains), with no allocation.
class SparseRangeSpace {
 public:
  explicit SparseRangeSpace(const CompiledModel& model);

  /// Solve with M = diag(m_diag), G values in tape order (G_pattern). Returns false when M has
  /// a non-positive entry or S is not positive definite (caller reports the failure).
  bool solve(const double* m_diag, const double* g_values, const double* rhs, const double* gamma,
             double* a, double* lambda);

 private:
  struct Contribution {
    size_t value;  // index into the envelope's values
    int g1, g2;    // G entries (same column j)
    int column;    // j
  };
  size_t n_, m_;
  std::vector<std::pair<size_t, size_t>> G_;  // (row, column) per G value
  std::vector<Contribution> contributions_;
  EnvelopeCholesky S_;
  Eigen::VectorXd a0_, lam_;
};

}  // namespace lagrange::dynamics
