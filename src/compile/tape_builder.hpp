#pragma once
// SSA construction of a tape with constant folding and value numbering, then dead-code
// elimination and register allocation. Used by both Tape::compile and Tape::specialize, so
// compile-time and specialisation-time folding follow the same rules (docs/theory.md §8).

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "compile/tape_code.hpp"

namespace lagrange::tape_detail {

/// One term coef·f₁·…·f_k of a sum; factors are SSA values.
struct Term {
  double coef = 1.0;
  std::vector<std::uint32_t> factors;
};

/// Builds an SSA instruction list: every method returns the SSA value of its result, folding
/// instructions whose operands are all constant and reusing an identical earlier instruction.
class TapeBuilder {
 public:
  /// A builder for a tape reading `num_inputs` inputs.
  explicit TapeBuilder(size_t num_inputs) : num_inputs_(num_inputs) {}

  /// The constant v.
  std::uint32_t constant(double v);
  /// Input number `index`.
  std::uint32_t input(std::uint32_t index);
  /// A one-operand op (Neg, Inv, Sqrt, Sin … Abs) of x.
  std::uint32_t unary(Op op, std::uint32_t x);
  /// A two-operand op (Div, Pow, Atan2) of (x, y).
  std::uint32_t binary(Op op, std::uint32_t x, std::uint32_t y);
  /// x^n for an integer n ≠ 0 with |n| ≤ kMaxPowInt.
  std::uint32_t pow_int(std::uint32_t x, int n);
  /// Σ terms + constant: constant factors fold into each term's coefficient, all-constant
  /// terms into the constant; emits Sum when every term has one factor, else SumProd.
  std::uint32_t sum(const std::vector<Term>& terms, double constant);
  /// coef·Π factors, constant factors folded into coef.
  std::uint32_t prod(double coef, const std::vector<std::uint32_t>& factors);

  /// True when SSA value v is a constant.
  bool is_constant(std::uint32_t v) const { return code_[v].op == Op::Const; }
  /// The value of constant v.
  double value(std::uint32_t v) const { return code_[v].c; }
  /// Number of SSA instructions so far (before dead-code elimination).
  size_t size() const { return code_.size(); }

  /// The finished tape computing `outputs`: instructions no output depends on are dropped and
  /// registers are reused once their last reader has run (linear scan, LIFO free list).
  TapeCode finish(const std::vector<std::uint32_t>& outputs) const;

 private:
  /// Appends `ins` with operand list (args, coeffs) unless an identical instruction exists.
  std::uint32_t emit(Instr ins, const std::vector<std::uint32_t>& args,
                     const std::vector<double>& coeffs);

  size_t num_inputs_;
  std::vector<Instr> code_;  ///< SSA: code_[v] writes value v
  std::vector<std::uint32_t> args_;
  std::vector<double> coeffs_;
  std::unordered_map<std::string, std::uint32_t> numbering_;  ///< instruction bytes → value
};

}  // namespace lagrange::tape_detail
