// docs/theory.md §8.2, "Samples checked before a run is called complete": when T + U is a
// constant of motion.
#include "lagrange/equations.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange {

namespace {

bool has_time(const Model& model, const GiNaC::ex& e) {
  return e.has(model.t);
}

}  // namespace

bool conserves_energy(const Equations& eq) {
  const Model& model = *eq.model;
  // Work done from outside: forces, dampers, torques (joint torques are generalised forces),
  // inputs (functions of t).
  if (!model.forces.empty() || !model.dampers.empty() || !model.torques.empty() ||
      !model.inputs.empty())
    return false;
  for (const GiNaC::ex& q : model.generalized_forces)
    if (!q.is_zero()) return false;
  // A Lagrangian or constraints that depend on t exchange energy with whatever moves them.
  if (has_time(model, eq.T) || has_time(model, eq.U)) return false;
  for (const GiNaC::ex& c : eq.C)
    if (has_time(model, c)) return false;
  // Velocity-dependent potentials make T + U differ from the energy function Σ v ∂L/∂v − L.
  for (const auto& [role, index] : symbolic::state_symbols(eq.kin, eq.U))
    if (role != 'q') return false;
  // So does a written kinetic energy with terms that are not quadratic in the velocities
  // (Euler's theorem: Σ v ∂T/∂v = 2T exactly for a homogeneous quadratic T). Particles and
  // bodies give quadratic forms; only the written part needs the test.
  if (!model.kinetic.is_zero()) {
    GiNaC::ex euler = -2 * model.kinetic;
    for (const auto& [role, index] : symbolic::state_symbols(eq.kin, model.kinetic))
      if (role == 'v') euler += eq.kin.v[index] * model.kinetic.diff(eq.kin.v[index]);
    if (!GiNaC::expand(euler).is_zero()) return false;
  }
  return true;
}

}  // namespace lagrange
