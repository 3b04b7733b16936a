// docs/theory.md §8.2, "Samples checked before a run is called complete": when T + U is a
// constant of motion.
#include "lagrange/equations.hpp"
#include "symbolic/expansion_bound.hpp"
#include "symbolic/memo_diff.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange {

bool conserves_energy(const Equations& eq) {
  const Model& model = *eq.model;
  // Work done from outside: forces, dampers, torques (joint torques are generalised forces),
  // inputs (functions of t).
  if (!model.forces.empty() || !model.dampers.empty() || !model.torques.empty() ||
      !model.inputs.empty())
    return false;
  for (const GiNaC::ex& q : model.generalized_forces)
    if (!q.is_zero()) return false;
  // Which of t and the velocities each expression contains, memoised over the DAG: a long
  // chain's recursive T shares its subtrees, which GiNaC's has() walks again at every use.
  std::vector<GiNaC::symbol> watched{model.t};
  watched.insert(watched.end(), eq.kin.v.begin(), eq.kin.v.end());
  symbolic::MemoDiff scan(watched);
  const auto has_time = [&](const GiNaC::ex& e) {
    const std::vector<size_t>& in = scan.columns_in(e);
    return !in.empty() && in.front() == 0;  // ascending: t is column 0
  };
  // A Lagrangian or constraints that depend on t exchange energy with whatever moves them.
  if (has_time(eq.T) || has_time(eq.U)) return false;
  for (const GiNaC::ex& c : eq.C)
    if (has_time(c)) return false;
  // Velocity-dependent potentials make T + U differ from the energy function Σ v ∂L/∂v − L.
  for (size_t k : scan.columns_in(eq.U))
    if (k > 0) return false;
  // So does a written kinetic energy with terms that are not quadratic in the velocities
  // (Euler's theorem: Σ v ∂T/∂v = 2T exactly for a homogeneous quadratic T). Particles and
  // bodies give quadratic forms; only the written part needs the test.
  if (!model.kinetic.is_zero()) {
    GiNaC::ex euler = -2 * model.kinetic;
    for (const auto& [role, index] : symbolic::state_symbols(eq.kin, model.kinetic))
      if (role == 'v') euler += eq.kin.v[index] * model.kinetic.diff(eq.kin.v[index]);
    // Expanded only within kDerivationTerms (issue 37 item 12): (Σqᵢ²)²⁰ in T once took minutes
    // and gigabytes here. Beyond, homogeneity is not established and T + U is not checked.
    if (!symbolic::expands_within(euler, symbolic::kDerivationTerms)) return false;
    if (!GiNaC::expand(euler).is_zero()) return false;
  }
  return true;
}

}  // namespace lagrange
