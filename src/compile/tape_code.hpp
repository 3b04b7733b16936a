#pragma once
// The raw arrays of a Tape and the scalar kernels shared by eval, constant folding and the C
// emitter, so that all three compute bit-identical values.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lagrange/tape.hpp"

namespace lagrange::tape_detail {

using Op = Tape::Op;
using Instr = Tape::Instr;

/// The arrays a Tape is made of, produced by TapeBuilder::finish.
struct TapeCode {
  size_t num_inputs = 0;
  size_t num_registers = 0;
  std::vector<Instr> code;
  std::vector<std::uint32_t> args;
  std::vector<double> coeffs;
  std::vector<std::uint32_t> outputs;
};

/// Largest |n| compiled as PowInt; larger integer powers go through pow().
constexpr int kMaxPowInt = 8;

/// x^n by repeated multiplication ((x·x)·x…), 1/x^|n| for n < 0; n ≠ 0. The C emitter prints
/// the same product, so interpreter and exported C agree bit for bit.
inline double pow_int(double x, int n) {
  const int m = n < 0 ? -n : n;
  double p = x;
  for (int k = 1; k < m; ++k) p *= x;
  return n < 0 ? 1.0 / p : p;
}

/// The value of a one-operand op (Neg, Inv, Sqrt, Sin … Abs) at x.
inline double apply_unary(Op op, double x) {
  switch (op) {
    case Op::Neg:
      return -x;
    case Op::Inv:
      return 1.0 / x;
    case Op::Sqrt:
      return std::sqrt(x);
    case Op::Sin:
      return std::sin(x);
    case Op::Cos:
      return std::cos(x);
    case Op::Tan:
      return std::tan(x);
    case Op::Asin:
      return std::asin(x);
    case Op::Acos:
      return std::acos(x);
    case Op::Atan:
      return std::atan(x);
    case Op::Sinh:
      return std::sinh(x);
    case Op::Cosh:
      return std::cosh(x);
    case Op::Tanh:
      return std::tanh(x);
    case Op::Exp:
      return std::exp(x);
    case Op::Log:
      return std::log(x);
    case Op::Abs:
      return std::fabs(x);
    default:
      return std::nan("");
  }
}

/// The value of a two-operand op (Div, Pow, Atan2) at (x, y).
inline double apply_binary(Op op, double x, double y) {
  switch (op) {
    case Op::Div:
      return x / y;
    case Op::Pow:
      return std::pow(x, y);
    case Op::Atan2:
      return std::atan2(x, y);
    default:
      return std::nan("");
  }
}

/// The C name of a one-argument math function op.
inline const char* c_function(Op op) {
  switch (op) {
    case Op::Sqrt:
      return "sqrt";
    case Op::Sin:
      return "sin";
    case Op::Cos:
      return "cos";
    case Op::Tan:
      return "tan";
    case Op::Asin:
      return "asin";
    case Op::Acos:
      return "acos";
    case Op::Atan:
      return "atan";
    case Op::Sinh:
      return "sinh";
    case Op::Cosh:
      return "cosh";
    case Op::Tanh:
      return "tanh";
    case Op::Exp:
      return "exp";
    case Op::Log:
      return "log";
    case Op::Abs:
      return "fabs";
    default:
      return nullptr;
  }
}

/// True for ops with one register operand in `a` (PowInt included).
inline bool is_unary(Op op) {
  return op == Op::Neg || op == Op::Inv || op == Op::PowInt ||
         (op >= Op::Sqrt && op <= Op::Abs && op != Op::Atan2);
}

/// True for ops with register operands in `a` and `b`.
inline bool is_binary(Op op) {
  return op == Op::Div || op == Op::Pow || op == Op::Atan2;
}

/// Calls f(register) for every register operand of `ins` (duplicates included).
template <class F>
void for_each_operand(const Instr& ins, const std::vector<std::uint32_t>& args, F&& f) {
  if (is_unary(ins.op)) {
    f(ins.a);
  } else if (is_binary(ins.op)) {
    f(ins.a);
    f(ins.b);
  } else if (ins.op == Op::Sum || ins.op == Op::Prod) {
    for (std::uint32_t i = 0; i < ins.b; ++i) f(args[ins.a + i]);
  } else if (ins.op == Op::SumProd) {
    std::uint32_t p = ins.a;
    for (std::uint32_t t = 0; t < ins.b; ++t) {
      const std::uint32_t k = args[p];
      for (std::uint32_t j = 1; j <= k; ++j) f(args[p + j]);
      p += k + 1;
    }
  }
}

/// Appends " + c" / " - |c|" when c ≠ 0, as eval adds it last; `write` prints |c| (the C and
/// text emitters print numbers differently).
template <class Write>
void append_constant(std::string& s, double c, Write write) {
  if (c != 0.0) s += (c < 0 ? " - " : " + ") + write(std::fabs(c));
}

}  // namespace lagrange::tape_detail
