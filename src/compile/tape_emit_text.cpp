// Tape::to_text: the tape as named common subexpressions, for `lagrange derive` of models whose
// full expansion is too large to print (the text grows with the tape, not with the expansion).

#include <fmt/format.h>

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

// The name of a one-argument function op in the model language (abs, not C's fabs).
std::string function_name(Op op) {
  return op == Op::Abs ? "abs" : tape_detail::c_function(op);
}

std::string number(double v) {
  return fmt::format("{}", v);
}

// coef·f₁·…·f_k with ±1 omitted; `first` chooses between a leading "-" and " - "/" + ".
void append_term(std::string& s, bool first, double coef, const std::vector<std::string>& f) {
  const bool negative = std::signbit(coef);
  s += first ? (negative ? "-" : "") : (negative ? " - " : " + ");
  const double mag = std::fabs(coef);
  if (mag != 1.0 || f.empty()) s += number(mag) + (f.empty() ? "" : "*");
  for (size_t j = 0; j < f.size(); ++j) s += (j ? "*" : "") + f[j];
}

}  // namespace

Tape::Text Tape::to_text(const std::vector<std::string>& input_names,
                         const std::string& prefix) const {
  if (input_names.size() != num_inputs_)
    throw std::invalid_argument(
        fmt::format("to_text: expected {} input names, got {}", num_inputs_, input_names.size()));
  const size_t n = code_.size();
  // The instruction that last wrote each register, the values each instruction reads, and how
  // often each value is read (by instructions and outputs).
  std::vector<std::uint32_t> writer(num_registers_, 0);
  std::vector<std::vector<std::uint32_t>> reads(n);
  std::vector<std::uint32_t> uses(n, 0);
  for (size_t k = 0; k < n; ++k) {
    tape_detail::for_each_operand(code_[k], args_, [&](std::uint32_t r) {
      reads[k].push_back(writer[r]);
      ++uses[writer[r]];
    });
    writer[code_[k].dst] = static_cast<std::uint32_t>(k);
  }
  std::vector<std::uint32_t> output_values;
  for (const std::uint32_t r : outputs_) {
    output_values.push_back(writer[r]);
    ++uses[writer[r]];
  }

  // text[k]: a name (number, input, prefix + k) for values read more than once, else the
  // expression, moved into its single reader. atomic[k]: needs no parentheses as an operand.
  std::vector<std::string> text(n);
  std::vector<bool> named(n, false), atomic(n, true);
  auto operand = [&](std::uint32_t v) {
    if (named[v]) return atomic[v] ? text[v] : "(" + text[v] + ")";
    std::string s = std::move(text[v]);
    return atomic[v] ? s : "(" + s + ")";
  };
  Text result;
  for (size_t k = 0; k < n; ++k) {
    const Instr& ins = code_[k];
    if (ins.op == Op::Const || ins.op == Op::Input) {
      named[k] = true;
      text[k] = ins.op == Op::Const ? number(ins.c) : input_names[ins.a];
      atomic[k] = ins.op == Op::Input || ins.c >= 0;
      continue;
    }
    std::vector<std::string> ops;
    for (const std::uint32_t v : reads[k]) ops.push_back(operand(v));
    std::string s;
    bool is_atomic = false;
    switch (ins.op) {
      case Op::Sum:
        for (std::uint32_t i = 0; i < ins.b; ++i)
          append_term(s, i == 0, coeffs_[ins.a + i], {ops[i]});
        tape_detail::append_constant(s, ins.c, number);
        break;
      case Op::SumProd: {
        std::uint32_t p = ins.a;
        size_t next = 0;
        for (std::uint32_t t = 0; t < ins.b; ++t) {
          const auto first = ops.begin() + static_cast<long>(next);
          append_term(s, t == 0, coeffs_[p], {first, first + static_cast<long>(args_[p])});
          next += args_[p];
          p += args_[p] + 1;
        }
        tape_detail::append_constant(s, ins.c, number);
        break;
      }
      case Op::Prod:
        append_term(s, true, ins.c, ops);
        break;
      case Op::Neg:
        s = "-" + ops[0];
        break;
      case Op::Inv:
        s = "1/" + ops[0];
        break;
      case Op::Div:
        s = ops[0] + "/" + ops[1];
        break;
      case Op::PowInt:
        s = fmt::format("{}^{}", ops[0], static_cast<int>(ins.c));
        break;
      case Op::Pow:
        s = ops[0] + "^" + ops[1];
        break;
      case Op::Atan2:
        s = fmt::format("atan2({}, {})", ops[0], ops[1]);
        is_atomic = true;
        break;
      default:
        s = fmt::format("{}({})", function_name(ins.op), ops[0]);
        is_atomic = true;
        break;
    }
    if (uses[k] > 1) {
      named[k] = true;
      text[k] = prefix + std::to_string(result.definitions.size() + 1);
      result.definitions.emplace_back(text[k], std::move(s));
    } else {
      text[k] = std::move(s);
      atomic[k] = is_atomic;
    }
  }
  for (const std::uint32_t v : output_values)
    result.outputs.push_back(named[v] ? text[v] : std::move(text[v]));
  return result;
}

}  // namespace lagrange
