// Tape::compile: GiNaC expression DAG → SSA tape with common subexpressions evaluated once.

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "compile/collect_factors.hpp"
#include "compile/ginac_util.hpp"
#include "compile/tape_builder.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

namespace {

using GiNaC::ex;
using tape_detail::ExMap;
using tape_detail::Op;
using tape_detail::PairAccess;
using tape_detail::TapeBuilder;
using tape_detail::Term;

/// Text of an expression for error messages.
std::string text(const ex& e) {
  std::ostringstream s;
  s << e;
  return s.str();
}

/// The double value of a real GiNaC numeric (rationals rounded to nearest).
double to_double(const ex& e) {
  const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
  if (!n.is_real()) {
    throw std::invalid_argument(fmt::format("cannot compile complex number {}", text(e)));
  }
  return n.to_double();
}

/// The tape op of a supported one-argument GiNaC function, by name.
const std::unordered_map<std::string, Op>& unary_functions() {
  static const std::unordered_map<std::string, Op> table = {
      {"sin", Op::Sin},   {"cos", Op::Cos},   {"tan", Op::Tan},   {"asin", Op::Asin},
      {"acos", Op::Acos}, {"atan", Op::Atan}, {"sinh", Op::Sinh}, {"cosh", Op::Cosh},
      {"tanh", Op::Tanh}, {"exp", Op::Exp},   {"log", Op::Log},   {"sqrt", Op::Sqrt},
      {"abs", Op::Abs}};
  return table;
}

/// Walks the expression DAG and emits one SSA value per distinct subexpression.
class ExprCompiler {
 public:
  /// A compiler emitting into `b`, with inputs[i] read as input i.
  ExprCompiler(TapeBuilder& b, const std::vector<GiNaC::symbol>& inputs) : b_(b) {
    for (size_t i = 0; i < inputs.size(); ++i) {
      if (!input_index_.emplace(inputs[i], static_cast<std::uint32_t>(i)).second) {
        throw std::invalid_argument(
            fmt::format("input symbol '{}' is listed twice", inputs[i].get_name()));
      }
    }
  }

  /// Counts how many parents reference each distinct subexpression of e (first visit recurses).
  void count_uses(const ex& e) {
    if (e.nops() == 0) return;
    if (uses_[e]++ > 0) return;
    if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
      for (const GiNaC::expair& p : PairAccess::pairs(GiNaC::ex_to<GiNaC::expairseq>(e))) {
        count_uses(p.rest);
        count_uses(p.coeff);
      }
    } else {
      for (size_t i = 0; i < e.nops(); ++i) count_uses(e.op(i));
    }
  }

  /// The SSA value of e, compiled once per distinct expression.
  std::uint32_t value(const ex& e) {
    if (auto it = memo_.find(e); it != memo_.end()) return it->second;
    const std::uint32_t v = build(e);
    memo_.emplace(e, v);
    return v;
  }

 private:
  /// Compiles e from its children (no memo lookup).
  std::uint32_t build(const ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return b_.constant(to_double(e));
    if (GiNaC::is_a<GiNaC::constant>(e)) return b_.constant(to_double(e.evalf()));
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto it = input_index_.find(e);
      if (it == input_index_.end()) {
        throw std::invalid_argument(
            fmt::format("unknown symbol '{}': it is not one of the tape's inputs",
                        GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
      }
      return b_.input(it->second);
    }
    if (GiNaC::is_a<GiNaC::add>(e)) return build_sum(GiNaC::ex_to<GiNaC::add>(e));
    if (GiNaC::is_a<GiNaC::mul>(e)) return build_product(GiNaC::ex_to<GiNaC::mul>(e));
    if (GiNaC::is_a<GiNaC::power>(e)) return power(e.op(0), e.op(1));
    if (GiNaC::is_a<GiNaC::function>(e)) return build_function(GiNaC::ex_to<GiNaC::function>(e));
    throw std::invalid_argument(fmt::format("cannot compile expression {}", text(e)));
  }

  /// base^exponent: integer exponents by PowInt/Inv, 1/2 by Sqrt, anything else by Pow.
  std::uint32_t power(const ex& base, const ex& exponent) {
    if (exponent.is_equal(GiNaC::ex(1))) return value(base);
    if (GiNaC::is_a<GiNaC::numeric>(exponent)) {
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(exponent);
      if (n.is_integer() && abs(n) <= tape_detail::kMaxPowInt) {
        return b_.pow_int(value(base), n.to_int());
      }
      if (n.is_equal(GiNaC::numeric(1, 2))) return b_.unary(Op::Sqrt, value(base));
    }
    return b_.binary(Op::Pow, value(base), value(exponent));
  }

  /// The factors of a sum's term rest: a once-used product is spliced into the sum (the fused
  /// sum of products of docs/theory.md §8), anything else is one factor.
  Term term(const ex& rest, const ex& coeff) {
    Term t{to_double(coeff), {}};
    if (GiNaC::is_a<GiNaC::mul>(rest) && uses_[rest] <= 1 && !memo_.count(rest)) {
      const auto& m = GiNaC::ex_to<GiNaC::mul>(rest);
      t.coef *= to_double(PairAccess::overall(m));
      for (const GiNaC::expair& f : PairAccess::pairs(m)) {
        t.factors.push_back(power(f.rest, f.coeff));
      }
    } else {
      t.factors.push_back(value(rest));
    }
    return t;
  }

  /// add → Sum / SumProd: Σ coeffᵢ·restᵢ + overall constant.
  std::uint32_t build_sum(const GiNaC::add& s) {
    std::vector<Term> terms;
    terms.reserve(PairAccess::pairs(s).size());
    for (const GiNaC::expair& p : PairAccess::pairs(s)) terms.push_back(term(p.rest, p.coeff));
    return b_.sum(terms, to_double(PairAccess::overall(s)));
  }

  /// mul → Prod, or Div(c·numerators, denominators) when some factors have exponent −1.
  std::uint32_t build_product(const GiNaC::mul& m) {
    std::vector<std::uint32_t> num, den;
    for (const GiNaC::expair& f : PairAccess::pairs(m)) {
      if (GiNaC::ex_to<GiNaC::numeric>(f.coeff).is_equal(-1)) {
        den.push_back(value(f.rest));
      } else {
        num.push_back(power(f.rest, f.coeff));
      }
    }
    const std::uint32_t top = b_.prod(to_double(PairAccess::overall(m)), num);
    if (den.empty()) return top;
    return b_.binary(Op::Div, top, b_.prod(1.0, den));
  }

  /// Supported functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt abs.
  std::uint32_t build_function(const GiNaC::function& f) {
    const std::string name = f.get_name();
    if (name == "atan2" && f.nops() == 2) {
      return b_.binary(Op::Atan2, value(f.op(0)), value(f.op(1)));
    }
    // Every tape value is real: conjugate and real part are the identity (they appear in
    // GiNaC's derivative of abs when an expression holds complex-domain symbols).
    if ((name == "conjugate" || name == "real_part") && f.nops() == 1) return value(f.op(0));
    const auto& table = unary_functions();
    if (auto it = table.find(name); it != table.end() && f.nops() == 1) {
      return b_.unary(it->second, value(f.op(0)));
    }
    throw std::invalid_argument(fmt::format(
        "cannot compile function '{}' (supported: sin cos tan asin acos atan atan2 sinh cosh "
        "tanh exp log sqrt abs)",
        name));
  }

  TapeBuilder& b_;
  ExMap<std::uint32_t> input_index_;
  ExMap<std::uint32_t> memo_;
  ExMap<int> uses_;
};

}  // namespace

Tape Tape::compile(const std::vector<GiNaC::ex>& outputs,
                   const std::vector<GiNaC::symbol>& inputs) {
  tape_detail::TapeBuilder builder(inputs.size());
  ExprCompiler compiler(builder, inputs);
  const std::vector<GiNaC::ex> rewritten = lagrange::collect_common_factors(outputs);
  for (const GiNaC::ex& e : rewritten) compiler.count_uses(e);
  std::vector<std::uint32_t> out;
  out.reserve(rewritten.size());
  for (const GiNaC::ex& e : rewritten) out.push_back(compiler.value(e));
  return from_code(builder.finish(out));
}

Tape Tape::from_code(tape_detail::TapeCode&& code) {
  Tape t;
  t.num_inputs_ = code.num_inputs;
  t.num_registers_ = code.num_registers;
  t.code_ = std::move(code.code);
  t.args_ = std::move(code.args);
  t.coeffs_ = std::move(code.coeffs);
  t.outputs_ = std::move(code.outputs);
  return t;
}

}  // namespace lagrange
