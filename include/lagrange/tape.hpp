#pragma once
// The one compiled representation: a common-subexpression-eliminated instruction tape.
// It is interpreted in C++ (no allocation per call) and emitted as C99 by `export`.

#include <ginac/ginac.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lagrange {

namespace tape_detail {
struct TapeCode;
}

/// An immutable straight-line program mapping a flat input array to a flat output array.
class Tape {
 public:
  /// A named intermediate value: the symbol stands for the expression in later definitions and
  /// in the outputs (how recursive algorithms stay linear in size, docs/theory.md §4.9).
  using Definition = std::pair<GiNaC::symbol, GiNaC::ex>;

  /// Compile `outputs` (expressions in `inputs` and the `definitions`' symbols, each definition
  /// in the inputs and earlier definitions) into a tape with shared subexpressions evaluated
  /// once. Throws std::invalid_argument naming any symbol that is neither.
  static Tape compile(const std::vector<GiNaC::ex>& outputs,
                      const std::vector<GiNaC::symbol>& inputs,
                      const std::vector<Definition>& definitions = {});

  size_t num_inputs() const { return num_inputs_; }
  size_t num_outputs() const { return outputs_.size(); }
  /// Number of scratch doubles `eval` needs.
  size_t work_size() const { return num_registers_; }
  size_t num_instructions() const { return code_.size(); }

  /// out[i] = output i at `in`; `work` has work_size() doubles. Never allocates.
  void eval(const double* in, double* out, double* work) const;

  /// The same tape with inputs [first, first + values.size()) fixed to `values` and constant
  /// folded (linear in tape size). The input layout is unchanged; fixed inputs are ignored.
  Tape specialize(size_t first, const std::vector<double>& values) const;

  /// C99 source of `void NAME(const double* in, double* out)`, self-contained (<math.h> only),
  /// computing exactly what eval computes.
  /// With `file_local`, the preamble (comment, #include) is left out and the function is
  /// `static`, for embedding in a larger generated file.
  std::string to_c(const std::string& function_name, bool file_local = false) const;
  /// C99 of `void NAME(const double* in, double* out, double* work)` for machine code
  /// (MachineCode): exported, no preamble; `work` has work_size() doubles.
  std::string to_native_c(const std::string& function_name) const;
  /// As to_native_c, but every constant (constants and coefficients, in the order of
  /// constants()) read from work[constants_at + i]: one compiled function then serves every
  /// tape of the same structure (all specialisations of one tape to parameter values that fold
  /// alike), computing what each one's eval computes, bit for bit (docs/theory.md §9.3).
  /// work needs constants_at + constants().size() doubles, constants_at ≥ work_size().
  std::string to_shared_c(const std::string& function_name, size_t constants_at) const;
  /// The constants to_shared_c reads, in its order.
  std::vector<double> constants() const;

  /// The tape as text through named common subexpressions (how `derive` prints large models):
  /// `definitions` holds (name, expression) for every value read more than once, in evaluation
  /// order, named prefix1, prefix2, …; `outputs` the expression of each output. Inputs appear
  /// under `input_names`, values read once in place; the text grows linearly with the tape.
  struct Text {
    std::vector<std::pair<std::string, std::string>> definitions;
    std::vector<std::string> outputs;
  };
  Text to_text(const std::vector<std::string>& input_names, const std::string& prefix = "x") const;

  /// Instruction set (public so tests and the emitter can inspect it). Operand layouts:
  /// Const c; Input in[a]; Sum Σᵢ coeffs_[a+i]·r[args_[a+i]] (i < b), then + c if c ≠ 0;
  /// Prod c·Πᵢ r[args_[a+i]]; PowInt r[a]^c by repeated multiplication (1/… if c < 0);
  /// Div, Pow, Atan2 of (r[a], r[b]); unary ops of r[a]. SumProd is the fused sum of
  /// products of docs/theory.md §8: b terms starting at args_[a], each stored as its factor count
  /// k = args_[p], coefficient coeffs_[p] and factor registers args_[p+1 … p+k]; the value is
  /// Σ coeff·r[f₁]·…·r[f_k] (left to right), then + c if c ≠ 0.
  // clang-format off
  enum class Op : std::uint8_t {
    Const, Input, Sum, Prod, Neg, Inv, Div, PowInt, Pow, Sqrt, Sin, Cos, Tan, Asin, Acos,
    Atan, Atan2, Sinh, Cosh, Tanh, Exp, Log, Abs, SumProd
  };
  // clang-format on
  /// One instruction: op applied to registers a and b (or inputs, arguments, c) into dst.
  struct Instr {
    Op op;
    std::uint32_t dst;    ///< register written
    std::uint32_t a = 0;  ///< first operand register, input index, or start in `args_`
    std::uint32_t b = 0;  ///< second operand register, or argument count
    double c = 0.0;       ///< constant, integer exponent, or leading coefficient
  };

 private:
  /// Adopt the arrays a TapeBuilder finished (shared by compile and specialize).
  static Tape from_code(tape_detail::TapeCode&& code);
  /// The C text behind to_c and to_native_c.
  std::string emit_c(const std::string& function_name, bool preamble, bool exported, bool scratch,
                     std::optional<size_t> constants_at) const;
  size_t num_inputs_ = 0;
  size_t num_registers_ = 0;
  std::vector<Instr> code_;
  std::vector<std::uint32_t> args_;     ///< operand lists of Sum/Prod
  std::vector<double> coeffs_;          ///< parallel to args_: coefficients of Sum / SumProd
  std::vector<std::uint32_t> outputs_;  ///< register of each output
};

}  // namespace lagrange
