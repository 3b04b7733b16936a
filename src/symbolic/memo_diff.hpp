#pragma once
// Symbolic partial derivatives of many expressions that share subexpressions (docs/theory.md
// §5.1): each node's derivative by each column is computed once, and not at all for columns the
// node does not contain.

#include <ginac/ginac.h>

#include <vector>

#include "compile/ginac_util.hpp"

namespace lagrange::symbolic {

/// ∂e/∂xₖ for the column symbols xₖ, memoised over the expression DAG (GiNaC's own diff walks
/// shared subtrees again for each expression and each symbol).
class MemoDiff {
 public:
  explicit MemoDiff(const std::vector<GiNaC::symbol>& columns);
  /// The columns inputs[columns[k]]: column k is the k-th chosen input.
  MemoDiff(const std::vector<GiNaC::symbol>& inputs, const std::vector<size_t>& columns);

  /// Columns that e contains, ascending.
  const std::vector<size_t>& columns_in(const GiNaC::ex& e);
  /// ∂e/∂x_k.
  GiNaC::ex diff(const GiNaC::ex& e, size_t k);

 private:
  template <class T>
  using Map = tape_detail::ExMap<T>;

  /// ∂f(a₁…a_n)/∂aᵢ as an expression of the arguments.
  GiNaC::ex partial(const GiNaC::ex& f, size_t i);

  std::vector<GiNaC::symbol> columns_;
  Map<size_t> column_of_;
  Map<std::vector<size_t>> deps_;
  std::vector<Map<GiNaC::ex>> memo_;  ///< per column
};

}  // namespace lagrange::symbolic
