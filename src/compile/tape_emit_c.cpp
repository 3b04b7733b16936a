// Tape::to_c: the tape as C99, one statement per instruction, with eval's operation order so
// that the compiled C and the interpreter agree bit for bit (docs/theory.md §8: tape-as-C compiles
// in seconds where C of the raw expressions takes minutes).

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "compile/tape_code.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

namespace {

using tape_detail::Op;

/// A C double literal that reads back as exactly v (shortest round-trip digits).
std::string literal(double v) {
  if (std::isnan(v)) return "NAN";
  if (std::isinf(v)) return v > 0 ? "HUGE_VAL" : "(-HUGE_VAL)";
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

/// "r[i]".
std::string reg(std::uint32_t i) {
  return fmt::format("r[{}]", i);
}

/// Appends term coef·r[f₁]·…·r[f_k] to `s`; `first` selects a leading "-" over " - "/" + ".
/// ±1 coefficients are omitted and a negative coefficient becomes a subtraction, both exact.
void append_term(std::string& s, bool first, double coef, const std::uint32_t* f, std::uint32_t k) {
  const bool negative = std::signbit(coef);
  const double mag = std::fabs(coef);
  if (first) {
    if (negative) s += '-';
  } else {
    s += negative ? " - " : " + ";
  }
  if (mag != 1.0) s += literal(mag) + "*";
  for (std::uint32_t j = 0; j < k; ++j) {
    if (j > 0) s += '*';
    s += reg(f[j]);
  }
}

/// Appends " + c" / " - |c|" when c ≠ 0, as eval adds it last.
void append_constant(std::string& s, double c) {
  if (c != 0.0) s += (c < 0 ? " - " : " + ") + literal(std::fabs(c));
}

/// The C name of a one-argument math function op.
const char* c_function(Op op) {
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

/// Appends the C statement of one instruction, with eval's operation order.
void append_statement(std::string& s, const Tape::Instr& ins,
                      const std::vector<std::uint32_t>& args, const std::vector<double>& coeffs) {
  s += "  " + reg(ins.dst) + " = ";
  switch (ins.op) {
    case Op::Const:
      s += literal(ins.c);
      break;
    case Op::Input:
      s += fmt::format("in[{}]", ins.a);
      break;
    case Op::Sum:
      for (std::uint32_t i = 0; i < ins.b; ++i) {
        append_term(s, i == 0, coeffs[ins.a + i], &args[ins.a + i], 1);
      }
      append_constant(s, ins.c);
      break;
    case Op::SumProd: {
      std::uint32_t p = ins.a;
      for (std::uint32_t t = 0; t < ins.b; ++t) {
        append_term(s, t == 0, coeffs[p], &args[p + 1], args[p]);
        p += args[p] + 1;
      }
      append_constant(s, ins.c);
      break;
    }
    case Op::Prod:
      append_term(s, true, ins.c, &args[ins.a], ins.b);
      break;
    case Op::Neg:
      s += "-" + reg(ins.a);
      break;
    case Op::Inv:
      s += "1.0/" + reg(ins.a);
      break;
    case Op::Div:
      s += reg(ins.a) + "/" + reg(ins.b);
      break;
    case Op::PowInt: {
      const int n = static_cast<int>(ins.c);
      std::string p = reg(ins.a);
      for (int k = 1; k < std::abs(n); ++k) p += "*" + reg(ins.a);
      s += n < 0 ? "1.0/(" + p + ")" : p;
      break;
    }
    case Op::Pow:
      s += fmt::format("pow({}, {})", reg(ins.a), reg(ins.b));
      break;
    case Op::Atan2:
      s += fmt::format("atan2({}, {})", reg(ins.a), reg(ins.b));
      break;
    default:
      s += fmt::format("{}({})", c_function(ins.op), reg(ins.a));
      break;
  }
  s += ";\n";
}

/// True when name is a valid C identifier.
bool is_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  for (char ch : name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  }
  return true;
}

}  // namespace

std::string Tape::to_c(const std::string& function_name, bool file_local) const {
  if (!is_identifier(function_name)) {
    throw std::invalid_argument(
        fmt::format("to_c: expected a C identifier as function name, got '{}'", function_name));
  }
  // Large tapes are split into static functions of kChunk statements sharing `r`: GCC's
  // combiner and register allocator are superlinear in function size (a 6.5k-instruction
  // tape compiled 4x faster at -O1 this way, with the same run time).
  constexpr size_t kChunk = 256;
  const bool split = code_.size() > kChunk;
  std::string s;
  s.reserve(256 + 40 * code_.size());
  if (!file_local)
    s += fmt::format(
        "/* Generated by lagrange: {} instructions, {} inputs, {} outputs. Compile with\n"
        "   -ffp-contract=off to reproduce the interpreter bit for bit. */\n"
        "#include <math.h>\n",
        code_.size(), num_inputs_, outputs_.size());
  const char* linkage = file_local ? "static " : "";
  const std::string registers =
      fmt::format("  double r[{}];\n", num_registers_ > 0 ? num_registers_ : 1);
  if (!split)
    s += fmt::format("\n{}void {}(const double* in, double* out) {{\n", linkage, function_name);
  if (!split) s += registers;
  for (size_t i = 0; i < code_.size(); ++i) {
    if (split && i % kChunk == 0) {
      if (i > 0) s += "}\n";
      s +=
          fmt::format("\nstatic void {}_part{}(const double* restrict in, double* restrict r) {{\n",
                      function_name, i / kChunk);
    }
    append_statement(s, code_[i], args_, coeffs_);
  }
  if (split) {
    s += fmt::format("}}\n\n{}void {}(const double* in, double* out) {{\n", linkage, function_name);
    s += registers;
    for (size_t k = 0; k * kChunk < code_.size(); ++k) {
      s += fmt::format("  {}_part{}(in, r);\n", function_name, k);
    }
  }
  for (size_t i = 0; i < outputs_.size(); ++i) {
    s += fmt::format("  out[{}] = {};\n", i, reg(outputs_[i]));
  }
  s += "}\n";
  return s;
}

}  // namespace lagrange
