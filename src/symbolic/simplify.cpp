#include "lagrange/equations.hpp"

namespace lagrange {

namespace {

// Expand and replace sin(x)² by 1 − cos(x)² (also inside higher powers).
GiNaC::ex fold_pythagoras(const GiNaC::ex& e) {
  const GiNaC::ex w = GiNaC::wild(0);
  return e.expand()
      .subs(GiNaC::pow(GiNaC::sin(w), 2) == 1 - GiNaC::pow(GiNaC::cos(w), 2),
            GiNaC::subs_options::algebraic)
      .expand();
}

}  // namespace

GiNaC::ex simplify(const GiNaC::ex& e) {
  const GiNaC::ex nd = e.normal().numer_denom();
  return (fold_pythagoras(nd.op(0)) / fold_pythagoras(nd.op(1))).normal();
}

}  // namespace lagrange
