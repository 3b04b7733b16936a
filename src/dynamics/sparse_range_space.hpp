#pragma once
// Sparse KKT solve for a block-diagonal mass matrix: Cartesian chains (1×1 blocks) and free
// bodies on them (a body's ω couples through its inertia, a 3×3 block).

#include <Eigen/Dense>
#include <vector>

#include "dynamics/envelope_cholesky.hpp"
#include "lagrange/compiled_model.hpp"

namespace lagrange::dynamics {

/// Range-space KKT solve when M is block diagonal with small blocks (docs/theory.md §4.3):
///   S = G M⁻¹ Gᵀ (sparse, pattern fixed at construction), S λ = G M⁻¹(h + Q) − γ,
///   a = M⁻¹(h + Q − Gᵀ λ).
/// S is factorised by an envelope Cholesky in the constraints' natural order, so the cost per
/// call is linear in the number of constraints for banded G (chains), with no allocation.
class SparseRangeSpace {
 public:
  /// Largest block of M (coupled velocities) the solve takes.
  static constexpr size_t kMaxBlock = 6;
  /// Whether M's pattern splits into blocks of at most kMaxBlock velocities.
  static bool suits(const CompiledModel& model);

  explicit SparseRangeSpace(const CompiledModel& model);

  /// Solve with M's values in tape order (M_pattern), G's likewise (G_pattern). Returns false
  /// when a block of M or S is not positive definite (the caller reports the failure).
  bool solve(const double* m_values, const double* g_values, const double* rhs, const double* gamma,
             double* a, double* lambda);
  /// Factorise M and S only (the first half of solve). False as for solve.
  bool factorize(const double* m_values, const double* g_values);
  /// The solve with the factors of the last factorize() or solve() and those G values: one more
  /// right-hand side (rhs, gamma) of the same KKT matrix (the differentiated KKT system).
  void solve_factored(const double* g_values, const double* rhs, const double* gamma, double* a,
                      double* lambda);
  /// The same for k right-hand sides at once, each matrix row-major: rhs (n × k), gamma (m × k);
  /// the accelerations into a (n × k). Row operations over all k columns (vectorised).
  void solve_factored(const double* g_values, size_t k, const double* rhs, const double* gamma,
                      double* a) const;

 private:
  using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlock, kMaxBlock>;
  struct Contribution {
    size_t value;    // index into the envelope's values
    int g1, g2;      // G entries whose columns share a block
    size_t inverse;  // index of (M⁻¹)_{column(g1), column(g2)} in inverse_
  };
  /// M⁻¹ x for each block, in place.
  void apply_inverse(double* x);
  /// M⁻¹ X for each block, in place, X row-major n × k.
  void apply_inverse_rows(double* X, size_t k) const;

  size_t n_, m_;
  std::vector<std::pair<size_t, size_t>> M_, G_;   // (row, column) per value
  std::vector<std::vector<size_t>> blocks_;        // velocities of each block, ascending
  std::vector<size_t> block_of_, local_, offset_;  // per velocity; offset_ per block into inverse_
  std::vector<double> inverse_, scratch_;
  std::vector<Contribution> contributions_;
  EnvelopeCholesky S_;
  Eigen::VectorXd a0_, lam_;
};

}  // namespace lagrange::dynamics
