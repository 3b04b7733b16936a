// Tape::to_c: the tape as C99, one statement per instruction, with eval's operation order so
// that the compiled C and the interpreter agree bit for bit (docs/theory.md §8: tape-as-C compiles
// in seconds where C of the raw expressions takes minutes).

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
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

/// Where a shared tape's constants are read (Tape::to_shared_c): `array[next]`, `next` counting
/// up from the first constant's index in the order of Tape::constants().
struct ConstantSlots {
  std::string array;
  size_t next = 0;
  std::string take() { return fmt::format("{}[{}]", array, next++); }
};

/// Appends the C statement of a shared tape's instruction: eval's operations in eval's order,
/// each constant read from `k`. Signed coefficients multiply (c·x = −(|c|·x) and y + c·x =
/// y − |c|·x exactly), ±1 ones too (1·x = x); the constant term is added only when it is not
/// zero, as in eval, so that choice is part of the text.
/// Only for the instructions that hold constants (Const, Sum, SumProd, Prod).
void append_shared_statement(std::string& s, const Tape::Instr& ins,
                             const std::vector<std::uint32_t>& args, ConstantSlots& k) {
  const auto term = [&](bool first, const std::uint32_t* f, std::uint32_t n) {
    s += (first ? "" : " + ") + k.take();
    for (std::uint32_t j = 0; j < n; ++j) s += "*" + reg(f[j]);
  };
  const auto constant_term = [&] {
    if (ins.c != 0.0) s += " + " + k.take();
  };
  switch (ins.op) {
    case Op::Const:
      s += "  " + reg(ins.dst) + " = " + k.take() + ";\n";
      return;
    case Op::Sum:
      s += "  " + reg(ins.dst) + " = ";
      for (std::uint32_t i = 0; i < ins.b; ++i) term(i == 0, &args[ins.a + i], 1);
      constant_term();
      s += ";\n";
      return;
    case Op::SumProd: {
      s += "  " + reg(ins.dst) + " = ";
      std::uint32_t p = ins.a;
      for (std::uint32_t t = 0; t < ins.b; ++t) {
        term(t == 0, &args[p + 1], args[p]);
        p += args[p] + 1;
      }
      constant_term();
      s += ";\n";
      return;
    }
    case Op::Prod:
      s += "  " + reg(ins.dst) + " = ";
      term(true, &args[ins.a], ins.b);
      s += ";\n";
      return;
    default:
      throw std::logic_error("append_shared_statement: an instruction without constants");
  }
}

bool holds_constants(Op op) {
  return op == Op::Const || op == Op::Sum || op == Op::SumProd || op == Op::Prod;
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
      tape_detail::append_constant(s, ins.c, literal);
      break;
    case Op::SumProd: {
      std::uint32_t p = ins.a;
      for (std::uint32_t t = 0; t < ins.b; ++t) {
        append_term(s, t == 0, coeffs[p], &args[p + 1], args[p]);
        p += args[p] + 1;
      }
      tape_detail::append_constant(s, ins.c, literal);
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
      s += fmt::format("{}({})", tape_detail::c_function(ins.op), reg(ins.a));
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

std::string Tape::emit_c(const std::string& function_name, bool preamble, bool exported,
                         bool scratch, std::optional<size_t> constants_at) const {
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
  if (preamble)
    s += fmt::format(
        "/* Generated by lagrange: {} instructions, {} inputs, {} outputs. Compile with\n"
        "   -ffp-contract=off to reproduce the interpreter bit for bit. */\n"
        "#include <math.h>\n",
        code_.size(), num_inputs_, outputs_.size());
  const char* linkage = exported ? "" : "static ";
  const std::string parameters =
      scratch ? "const double* in, double* out, double* work" : "const double* in, double* out";
  // A split tape keeps its registers in the caller's scratch array when it has one: a large
  // tape's registers would not fit on a thread's stack. Small tapes keep a local array, which
  // the compiler turns into machine registers.
  const std::string registers =
      split && scratch ? "  double* r = work;\n"
                       : fmt::format("  double r[{}];\n", num_registers_ > 0 ? num_registers_ : 1);
  const std::string unused = scratch && !split && !constants_at ? "  (void)work;\n" : "";
  // A shared tape's constants follow the registers in `work`, which a split tape's parts know
  // as `r`.
  ConstantSlots k{split ? "r" : "work", constants_at.value_or(0)};
  if (!split) s += fmt::format("\n{}void {}({}) {{\n", linkage, function_name, parameters);
  if (!split) s += registers + unused;
  for (size_t i = 0; i < code_.size(); ++i) {
    if (split && i % kChunk == 0) {
      if (i > 0) s += "}\n";
      s +=
          fmt::format("\nstatic void {}_part{}(const double* restrict in, double* restrict r) {{\n",
                      function_name, i / kChunk);
    }
    if (constants_at && holds_constants(code_[i].op))
      append_shared_statement(s, code_[i], args_, k);
    else
      append_statement(s, code_[i], args_, coeffs_);
  }
  if (split) {
    s += fmt::format("}}\n\n{}void {}({}) {{\n", linkage, function_name, parameters);
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

std::string Tape::to_c(const std::string& function_name, bool file_local) const {
  return emit_c(function_name, !file_local, !file_local, false, std::nullopt);
}

std::string Tape::to_native_c(const std::string& function_name) const {
  return emit_c(function_name, false, true, true, std::nullopt);
}

std::string Tape::to_shared_c(const std::string& function_name, size_t constants_at) const {
  return emit_c(function_name, false, true, true, constants_at);
}

std::vector<double> Tape::constants() const {
  std::vector<double> k;
  for (const Instr& ins : code_) {
    switch (ins.op) {
      case Op::Const:
      case Op::Prod:
        k.push_back(ins.c);
        break;
      case Op::Sum:
        for (std::uint32_t i = 0; i < ins.b; ++i) k.push_back(coeffs_[ins.a + i]);
        if (ins.c != 0.0) k.push_back(ins.c);
        break;
      case Op::SumProd: {
        std::uint32_t p = ins.a;
        for (std::uint32_t t = 0; t < ins.b; ++t) {
          k.push_back(coeffs_[p]);
          p += args_[p] + 1;
        }
        if (ins.c != 0.0) k.push_back(ins.c);
        break;
      }
      default:
        break;
    }
  }
  return k;
}

}  // namespace lagrange
