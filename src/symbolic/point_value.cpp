// Memoised evaluation of an expression DAG at a point (src/symbolic/point_value.hpp).

#include "symbolic/point_value.hpp"

#include <stdexcept>
#include <string>

namespace lagrange::symbolic {

namespace {

using tape_detail::PairAccess;

GiNaC::numeric as_numeric(const GiNaC::ex& e) {
  const GiNaC::ex v = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v))
    throw std::invalid_argument(std::string("PointValue: '") +
                                GiNaC::ex_to<GiNaC::basic>(e).class_name() +
                                "' does not evaluate to a number");
  return GiNaC::ex_to<GiNaC::numeric>(v);
}

}  // namespace

GiNaC::numeric PointValue::operator()(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return GiNaC::ex_to<GiNaC::numeric>(e);
  if (const auto it = memo_.find(e); it != memo_.end()) return it->second;
  GiNaC::numeric v = compute(e);
  memo_.emplace(e, v);
  return v;
}

GiNaC::numeric PointValue::compute(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto it = at_.find(e);
    if (it == at_.end() || !GiNaC::is_a<GiNaC::numeric>(it->second))
      throw std::invalid_argument("PointValue: no value for the symbol '" +
                                  GiNaC::ex_to<GiNaC::symbol>(e).get_name() + "'");
    return GiNaC::ex_to<GiNaC::numeric>(it->second);
  }
  // Sums and products through their (rest, coeff) pairs: op(i) would build a new node per
  // term, which the memo could not recognise.
  if (GiNaC::is_a<GiNaC::add>(e)) {
    const auto& s = GiNaC::ex_to<GiNaC::add>(e);
    GiNaC::numeric v = GiNaC::ex_to<GiNaC::numeric>(PairAccess::overall(s));
    for (const GiNaC::expair& p : PairAccess::pairs(s))
      v += (*this)(p.rest) * GiNaC::ex_to<GiNaC::numeric>(p.coeff);
    return v;
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    const auto& s = GiNaC::ex_to<GiNaC::mul>(e);
    GiNaC::numeric v = GiNaC::ex_to<GiNaC::numeric>(PairAccess::overall(s));
    for (const GiNaC::expair& p : PairAccess::pairs(s))
      v *= GiNaC::pow((*this)(p.rest), GiNaC::ex_to<GiNaC::numeric>(p.coeff));
    return v;
  }
  if (GiNaC::is_a<GiNaC::power>(e)) return GiNaC::pow((*this)(e.op(0)), (*this)(e.op(1)));
  if (GiNaC::is_a<GiNaC::function>(e)) {
    GiNaC::ex f = e;  // the same function of its arguments' values
    for (size_t i = 0; i < e.nops(); ++i) f.let_op(i) = (*this)(e.op(i));
    return as_numeric(f);
  }
  return as_numeric(e.subs(at_));  // constants (Pi) and anything else without a rule
}

}  // namespace lagrange::symbolic
