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

// Model symbols are real: conjugate(x) = x (GiNaC's d/dx |x| produces conjugates, and a
// wildcard pattern cannot match them because conjugate(wild) evaluates to the wildcard).
struct DropConjugates : GiNaC::map_function {
  GiNaC::ex operator()(const GiNaC::ex& e) override {
    if (GiNaC::is_a<GiNaC::function>(e) &&
        GiNaC::ex_to<GiNaC::function>(e).get_name() == "conjugate")
      return (*this)(e.op(0));
    return e.map(*this);
  }
};

GiNaC::ex drop_conjugates(const GiNaC::ex& e) {
  DropConjugates f;
  return f(e);
}

}  // namespace

GiNaC::ex simplify(const GiNaC::ex& e) {
  const GiNaC::ex nd = drop_conjugates(e).normal().numer_denom();
  return (fold_pythagoras(nd.op(0)) / fold_pythagoras(nd.op(1))).normal();
}

}  // namespace lagrange
