#pragma once
// Where each value and derivative of the Jacobian tape goes in the implicit form's sparse
// matrices (docs/theory.md §5.1, "Implicit form"): fixed once per DynamicsJacobian, so that
// assembling them at a state is one pass over the tape's outputs.

#include <utility>
#include <vector>

#include "lagrange/analysis.hpp"

namespace lagrange::analysis_detail {

class KktLayout {
 public:
  /// `pattern` (value index, column) per derivative after the tape's `values` leading values;
  /// `columns` derivative columns (q, v, then inputs).
  KktLayout(const CompiledModel& cm, const std::vector<std::pair<size_t, size_t>>& pattern,
            size_t values, size_t columns);

  /// K, Phi_x and qdot_x of `out` (the tape's outputs) at the accelerations a, multipliers λ and
  /// Baumgarte rate α.
  void assemble(const double* out, const double* a, const double* lambda, double alpha,
                ImplicitJacobian& J) const;

 private:
  /// What multiplies a tape output on its way into a matrix entry.
  enum class Factor : unsigned char { one, minus_one, a, lambda, two_alpha, alpha_squared };
  struct Term {
    size_t source;  ///< index into the tape's outputs
    size_t dest;    ///< index into the matrix's values
    Factor factor;
    size_t index;  ///< of a or λ
  };
  struct Scatter {
    Eigen::SparseMatrix<double> pattern;
    std::vector<Term> terms;
    /// Fix `pattern` from the terms' (row, column) and point each term at its value.
    void finish(long rows, long cols, const std::vector<std::pair<long, long>>& where);
    void fill(const double* out, const double* a, const double* lambda, double alpha,
              Eigen::SparseMatrix<double>& into) const;
  };
  Scatter K_, Phi_, qdot_;
};

}  // namespace lagrange::analysis_detail
