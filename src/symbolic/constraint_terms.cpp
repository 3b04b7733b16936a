#include "lagrange/error.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

// docs/theory.md §4.3, index reduction: Ċ = Σⱼ ∂C/∂qⱼ q̇ⱼ + ∂ₜC, G = ∂Ċ/∂v (for q̇ = v this is
// ∂C/∂q; for a free body's ω it is the row 2P(∂C/∂R) of §4.4), C̈ = G a + c with
// c = dĊ/dt at a = 0. ∂C/∂q is kept for the position projection.
void add_constraint_terms(const Kinematics& kin, Equations& eq) {
  const Model& model = *kin.model;
  const size_t nq = kin.q.size(), nv = kin.v.size();
  eq.m = model.constraints.size();
  eq.G = GiNaC::matrix(static_cast<unsigned>(eq.m), static_cast<unsigned>(nv));
  eq.Cq = GiNaC::matrix(static_cast<unsigned>(eq.m), static_cast<unsigned>(nq));
  for (size_t r = 0; r < eq.m; ++r) {
    const NamedExpr& con = model.constraints[r];
    if (depends_on_rates(kin, con.expr))
      throw ModelError(con.loc, "constraint '" + con.name +
                                    "' depends on velocities; expected a holonomic constraint "
                                    "C(q, t) = 0");
    eq.C.push_back(con.expr);
    for (size_t j : coordinates_in(kin, con.expr)) eq.Cq(r, j) = con.expr.diff(kin.q[j]);
    const GiNaC::ex cdot = derivative_without_accelerations(kin, con.expr);
    for (size_t k : velocities_in(kin, cdot)) eq.G(r, k) = cdot.diff(kin.v[k]);
    eq.Cdot.push_back(cdot);
    eq.c.push_back(derivative_without_accelerations(kin, cdot));
  }
}

}  // namespace lagrange::symbolic
