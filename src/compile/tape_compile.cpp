// Tape::compile: GiNaC expression DAG → SSA tape with common subexpressions evaluated once.

#include <fmt/format.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "compile/canonical_order.hpp"
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

/// Walks the expression DAG and emits one SSA value per distinct canonical subexpression R(e)
/// (compile/canonical_order.hpp), visiting the operands of sums and products in canonical order
/// and with the signs of the canonical form; GiNaC's order and signs depend on load addresses
/// and symbol creation order. So the tape is the same in every process.
class ExprCompiler {
 public:
  /// A compiler emitting into `b`, with inputs[i] read as input i, operands taken in `order`.
  ExprCompiler(TapeBuilder& b, const std::vector<GiNaC::symbol>& inputs,
               tape_detail::CanonicalOrder& order)
      : b_(b), order_(order) {
    for (size_t i = 0; i < inputs.size(); ++i) {
      if (!input_index_.emplace(inputs[i], static_cast<std::uint32_t>(i)).second) {
        throw std::invalid_argument(
            fmt::format("input symbol '{}' is listed twice", inputs[i].get_name()));
      }
    }
  }

  /// From now on the symbol `name` reads SSA value v (a definition, Tape::Definition).
  void define(const GiNaC::symbol& name, std::uint32_t v) {
    if (input_index_.count(name) > 0 || !defined_.emplace(name, v).second)
      throw std::invalid_argument(
          fmt::format("symbol '{}' is defined twice or is also an input", name.get_name()));
  }

  /// Counts how many parents reference each distinct canonical subexpression of e (first visit
  /// recurses).
  void count_uses(const ex& e) {
    if (e.nops() == 0) return;
    if (slot(uses_, order_.id(e), 0)++ > 0) return;
    if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
      for (const GiNaC::expair& p : PairAccess::pairs(GiNaC::ex_to<GiNaC::expairseq>(e))) {
        count_uses(p.rest);
        count_uses(p.coeff);
      }
    } else {
      for (size_t i = 0; i < e.nops(); ++i) count_uses(e.op(i));
    }
  }

  /// The SSA value of e: that of its canonical form R(e), or of −R(e) when e = −R(e) (a sum
  /// or product with its signs flipped rather than an extra negation).
  std::uint32_t value(const ex& e) {
    if (order_.sign(e) > 0) return canonical_value(e);
    const std::uint32_t id = order_.id(e);
    if (const std::uint32_t v = slot(negated_, id, kNone); v != kNone) return v;
    std::uint32_t v = 0;
    if (GiNaC::is_a<GiNaC::add>(e)) {
      v = build_sum(e, -1);
    } else if (GiNaC::is_a<GiNaC::mul>(e)) {
      v = build_product(e, -1);
    } else {
      v = b_.unary(Op::Neg, canonical_value(e));
    }
    slot(negated_, id, kNone) = v;
    return v;
  }

 private:
  /// The SSA value of R(e), compiled once per canonical form.
  std::uint32_t canonical_value(const ex& e) {
    const std::uint32_t id = order_.id(e);
    if (const std::uint32_t v = slot(memo_, id, kNone); v != kNone) return v;
    const std::uint32_t v = build(e);
    slot(memo_, id, kNone) = v;
    return v;
  }

  /// Compiles R(e) from its children (no memo lookup).
  std::uint32_t build(const ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return b_.constant(to_double(e));
    if (GiNaC::is_a<GiNaC::constant>(e)) return b_.constant(to_double(e.evalf()));
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto it = input_index_.find(e);
      if (it != input_index_.end()) return b_.input(it->second);
      if (auto d = defined_.find(e); d != defined_.end()) return d->second;
      throw std::invalid_argument(
          fmt::format("unknown symbol '{}': it is not one of the tape's inputs",
                      GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
    }
    if (GiNaC::is_a<GiNaC::add>(e)) return build_sum(e, 1);
    if (GiNaC::is_a<GiNaC::mul>(e)) return build_product(e, 1);
    if (GiNaC::is_a<GiNaC::power>(e)) return power(e.op(0), e.op(1));
    if (GiNaC::is_a<GiNaC::function>(e)) return build_function(GiNaC::ex_to<GiNaC::function>(e));
    throw std::invalid_argument(fmt::format("cannot compile expression {}", text(e)));
  }

  /// R(base^exponent): integer exponents (whose sign the canonical form moves out) of R(base)
  /// by PowInt/Inv, or Pow beyond kMaxPowInt; 1/2 by Sqrt and anything else by Pow of base.
  std::uint32_t power(const ex& base, const ex& exponent) {
    if (exponent.is_equal(GiNaC::ex(1))) return canonical_value(base);
    if (GiNaC::is_a<GiNaC::numeric>(exponent)) {
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(exponent);
      if (n.is_integer() && abs(n) <= tape_detail::kMaxPowInt) {
        return b_.pow_int(canonical_value(base), n.to_int());
      }
      if (n.is_integer()) return b_.binary(Op::Pow, canonical_value(base), value(exponent));
      if (n.is_equal(GiNaC::numeric(1, 2))) return b_.unary(Op::Sqrt, value(base));
    }
    return b_.binary(Op::Pow, value(base), value(exponent));
  }

  /// The term coef·R(rest) of a sum: a once-used product is spliced into the sum (the fused
  /// sum of products of docs/theory.md §8), anything else is one factor.
  Term term(const ex& rest, double coef) {
    Term t{coef, {}};
    const std::uint32_t id = order_.id(rest);
    if (GiNaC::is_a<GiNaC::mul>(rest) && slot(uses_, id, 0) <= 1 &&
        slot(memo_, id, kNone) == kNone) {
      const auto& m = GiNaC::ex_to<GiNaC::mul>(rest);
      t.coef *= std::fabs(to_double(PairAccess::overall(m)));
      const GiNaC::epvector& factors = PairAccess::pairs(m);
      for (std::uint32_t i : order_.pair_order(rest)) {
        t.factors.push_back(power(factors[i].rest, factors[i].coeff));
      }
    } else {
      t.factors.push_back(canonical_value(rest));
    }
    return t;
  }

  /// flip·R(add) → Sum / SumProd: Σ coeffᵢ·R(restᵢ) + constant, flip = ±1.
  std::uint32_t build_sum(const ex& e, int flip) {
    const auto& s = GiNaC::ex_to<GiNaC::add>(e);
    const GiNaC::epvector& pairs = PairAccess::pairs(s);
    const int sign = flip * order_.sign(e);
    std::vector<Term> terms;
    terms.reserve(pairs.size());
    for (std::uint32_t i : order_.pair_order(e)) {
      const double c = to_double(pairs[i].coeff);
      terms.push_back(term(pairs[i].rest, sign * order_.sign(pairs[i].rest) < 0 ? -c : c));
    }
    const double constant = to_double(PairAccess::overall(s));
    return b_.sum(terms, sign < 0 ? -constant : constant);
  }

  /// flip·R(mul) → Prod, or Div(±|c|·numerators, denominators) when some factors have
  /// exponent −1; flip = ±1.
  std::uint32_t build_product(const ex& e, int flip) {
    const auto& m = GiNaC::ex_to<GiNaC::mul>(e);
    const GiNaC::epvector& pairs = PairAccess::pairs(m);
    std::vector<std::uint32_t> num, den;
    for (std::uint32_t i : order_.pair_order(e)) {
      const GiNaC::expair& f = pairs[i];
      if (GiNaC::ex_to<GiNaC::numeric>(f.coeff).is_equal(-1)) {
        den.push_back(canonical_value(f.rest));
      } else {
        num.push_back(power(f.rest, f.coeff));
      }
    }
    const std::uint32_t top = b_.prod(flip * std::fabs(to_double(PairAccess::overall(m))), num);
    if (den.empty()) return top;
    return b_.binary(Op::Div, top, b_.prod(1.0, den));
  }

  /// Supported functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp log sqrt abs.
  std::uint32_t build_function(const GiNaC::function& f) {
    const std::string name = f.get_name();
    // A formal derivative D[0](conjugate)(x) appears in GiNaC's second derivative of abs: for
    // real values conjugate and real part have derivative 1 (0 from the second on), the
    // imaginary part 0. It must not fall through to the function itself (GiNaC names a
    // derivative after its function): that made d²|x|/dx² = 1/|x| instead of 0.
    if (GiNaC::is_a<GiNaC::fderivative>(f)) {
      const size_t order = GiNaC::ex_to<GiNaC::fderivative>(f).derivatives().size();
      if ((name == "conjugate" || name == "real_part") && f.nops() == 1)
        return b_.constant(order == 1 ? 1.0 : 0.0);
      if (name == "imag_part" && f.nops() == 1) return b_.constant(0.0);
      throw std::invalid_argument(
          fmt::format("cannot compile a derivative of the function '{}' (it has none in closed "
                      "form)",
                      name));
    }
    if (name == "atan2" && f.nops() == 2) {
      return b_.binary(Op::Atan2, value(f.op(0)), value(f.op(1)));
    }
    // Every tape value is real: conjugate and real part are the identity and the imaginary part
    // is 0 (they appear in GiNaC's derivative of abs, and in its abs of a power, when an
    // expression holds complex-domain symbols).
    if ((name == "conjugate" || name == "real_part") && f.nops() == 1) return value(f.op(0));
    if (name == "imag_part" && f.nops() == 1) return b_.constant(0.0);
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
  tape_detail::CanonicalOrder& order_;
  ExMap<std::uint32_t> input_index_;
  ExMap<std::uint32_t> defined_;  ///< definition symbols → their SSA values
  /// v[id], growing v with `fill` as needed (the reference lasts until v grows again).
  template <class T>
  static T& slot(std::vector<T>& v, std::uint32_t id, T fill) {
    if (id >= v.size()) v.resize(id + 1, fill);
    return v[id];
  }

  // Indexed by the canonical id of R(e) (CanonicalOrder::id); kNone: not compiled yet.
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> memo_;     ///< SSA value of R(e)
  std::vector<std::uint32_t> negated_;  ///< SSA value of −R(e)
  std::vector<int> uses_;               ///< number of parents of R(e)
};

}  // namespace

Tape Tape::compile(const std::vector<GiNaC::ex>& outputs, const std::vector<GiNaC::symbol>& inputs,
                   const std::vector<Definition>& definitions) {
  tape_detail::TapeBuilder builder(inputs.size());
  // Definition symbols are identified by position too, after the inputs: names may repeat.
  std::vector<GiNaC::symbol> named = inputs;
  std::vector<GiNaC::ex> all;
  all.reserve(definitions.size() + outputs.size());
  for (const auto& [name, value] : definitions) {
    named.push_back(name);
    all.push_back(value);
  }
  all.insert(all.end(), outputs.begin(), outputs.end());
  tape_detail::CanonicalOrder order(named);
  ExprCompiler compiler(builder, inputs, order);
  const std::vector<GiNaC::ex> rewritten = lagrange::collect_common_factors(all, order);
  for (const GiNaC::ex& e : rewritten) compiler.count_uses(e);
  for (size_t i = 0; i < definitions.size(); ++i)
    compiler.define(definitions[i].first, compiler.value(rewritten[i]));
  std::vector<std::uint32_t> out;
  out.reserve(outputs.size());
  for (size_t i = definitions.size(); i < rewritten.size(); ++i)
    out.push_back(compiler.value(rewritten[i]));
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
