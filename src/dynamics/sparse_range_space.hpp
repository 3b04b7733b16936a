#pragma once
// Sparse KKT solve for a block-diagonal mass matrix: Cartesian chains (1×1 blocks) and free
// bodies on them (a body's ω couples through its inertia, a 3×3 block).

#include <cstdint>
#include <utility>
#include <vector>

#include "dynamics/envelope_cholesky.hpp"
#include "lagrange/compiled_model.hpp"

namespace lagrange::dynamics {

/// (row, column) of each stored value of a sparse matrix, in the order the values come.
using Pattern = std::vector<std::pair<size_t, size_t>>;

/// Range-space KKT solve when M is block diagonal with small blocks (docs/theory.md §4.3):
///   S = G M⁻¹ Gᵀ (sparse, pattern fixed at construction), S λ = G M⁻¹(h + Q) − γ,
///   a = M⁻¹(h + Q − Gᵀ λ).
/// Everything that depends only on the patterns of M and G — M's blocks, G by rows and by
/// columns, the envelope of S and which products of G and M⁻¹ entries add into each of its
/// values — is worked out at construction; a call is arithmetic on preallocated storage
/// (docs/theory.md §4.3, "The KKT solve without per-call overhead"). S is factorised by an
/// envelope L D Lᵀ in the constraints' natural order, so the cost per call is linear in the
/// number of constraints for banded G (chains), with no allocation.
class SparseRangeSpace {
 public:
  /// Largest block of M (coupled velocities) the solve takes.
  static constexpr size_t kMaxBlock = 6;
  /// Whether M's pattern splits into blocks of at most kMaxBlock velocities.
  static bool suits(const CompiledModel& model);
  /// The same for an n × n M given by the pattern of its upper triangle.
  static bool suits(size_t n, const Pattern& M);

  explicit SparseRangeSpace(const CompiledModel& model);
  /// M (n × n, the pattern of its upper triangle) and G (m × n) given directly; S counts as
  /// singular when its smallest pivot is not above `singular_below` times its largest diagonal
  /// entry.
  SparseRangeSpace(size_t n, size_t m, const Pattern& M, const Pattern& G,
                   double singular_below = 1e-13);

  /// Solve with M's values in pattern order (M_pattern), G's likewise (G_pattern). Returns false
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
  /// A block of M of more than one velocity: its velocities (ascending), where its inverse
  /// starts in inverse_, and its M values as (value index, position in the k × k block).
  struct Block {
    std::vector<uint32_t> velocities;
    size_t offset = 0;
    std::vector<std::pair<uint32_t, uint32_t>> entries;
  };
  /// One term g[g1] · inverse_[inverse] · g[g2] of a value of S.
  struct Contribution {
    uint32_t g1, g2, inverse;
  };
  /// x ← M⁻¹ x over the blocks of more than one velocity (the 1×1 ones are scaled by the caller).
  void apply_blocks(double* x) const;
  /// X ← M⁻¹ X, X row-major n × k.
  void apply_inverse_rows(double* X, size_t k) const;

  size_t n_, m_;
  double singular_below_;
  bool structurally_singular_ = false;  // a velocity with no diagonal entry of M at all
  std::vector<uint32_t> scalar_velocity_, scalar_value_;  // 1×1 blocks: velocity, its M value
  bool scalars_contiguous_ = false;  // both ascending by one (point masses in M's order)
  std::vector<Block> blocks_;
  // 1/M_jj for velocity j of a 1×1 block, 1 for the others (first n values), then the inverses
  // of the larger blocks, k × k each.
  std::vector<double> inverse_;
  std::vector<uint32_t> row_start_, row_value_, row_column_;  // G by rows (pattern order kept)
  std::vector<uint32_t> column_start_, column_value_, column_row_;  // G by columns
  std::vector<uint32_t> s_start_;  // contributions of S value v: s_start_[v] … s_start_[v + 1]
  std::vector<Contribution> contributions_;
  EnvelopeCholesky S_;
  std::vector<double> a0_, lam_;
};

}  // namespace lagrange::dynamics
