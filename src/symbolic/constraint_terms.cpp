#include "lagrange/error.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

// DESIGN.md §4.3, index reduction: G = ∂C/∂q, Ċ = G v + ∂ₜC,
// C̈ = G a + c with c = Σⱼ ∂Ċ/∂qⱼ vⱼ + ∂ₜĊ (which holds (∂(Gv)/∂q)v + 2(∂G/∂t)v + ∂²C/∂t²).
void add_constraint_terms(const Model& model, Equations& eq) {
  const size_t n = model.coordinates.size();
  eq.m = model.constraints.size();
  eq.G = GiNaC::matrix(static_cast<unsigned>(eq.m), static_cast<unsigned>(n));
  for (size_t r = 0; r < eq.m; ++r) {
    const NamedExpr& con = model.constraints[r];
    if (depends_on_rates(model, con.expr))
      throw ModelError(con.loc, "constraint '" + con.name +
                                    "' depends on velocities; expected a holonomic constraint "
                                    "C(q, t) = 0");
    eq.C.push_back(con.expr);
    for (size_t j = 0; j < n; ++j) eq.G(r, j) = con.expr.diff(model.coordinates[j].q);
    const GiNaC::ex cdot = derivative_without_accelerations(model, con.expr);
    eq.Cdot.push_back(cdot);
    eq.c.push_back(derivative_without_accelerations(model, cdot));
  }
}

}  // namespace lagrange::symbolic
