#include "simulation/row_writer.hpp"

#include <cmath>

#include "simulation/max_abs.hpp"

namespace lagrange {

RowWriter::RowWriter(const CompiledModel& cm)
    : obs_(cm.observables.num_outputs()),
      qdot_(cm.nq),
      a_(cm.nv),
      lambda_(cm.m),
      C_(cm.m),
      Cdot_(cm.m) {}

// docs/theory.md §4.11: each part Σ coefficient · (a, λ or 1); three parts give a length.
double RowWriter::load_value(const LoadColumn& load) const {
  double square = 0, value = 0;
  for (const auto& part : load.parts) {
    value = 0;
    for (const LoadTerm& term : part) {
      const double factor = term.acceleration >= 0 ? a_[static_cast<size_t>(term.acceleration)]
                            : term.multiplier >= 0 ? lambda_[static_cast<size_t>(term.multiplier)]
                                                   : 1.0;
      value += obs_[term.observable] * factor;
    }
    square += value * value;
  }
  return load.parts.size() == 1 ? value : std::sqrt(square);
}

void RowWriter::append(Dynamics& dyn, double t, const double* q, const double* v,
                       Trajectory& traj) {
  write(dyn, t, q, v, traj.data);
}

void RowWriter::write(Dynamics& dyn, double t, const double* q, const double* v,
                      std::vector<double>& d) {
  const CompiledModel& cm = dyn.model();
  d.push_back(t);
  d.insert(d.end(), q, q + cm.nq);
  d.insert(d.end(), v, v + cm.nv);
  dyn.observe(t, q, v, obs_.data());
  d.insert(d.end(), {obs_[0], obs_[1], obs_[0] + obs_[1]});
  const auto reactions = obs_.begin() + 2 + static_cast<long>(cm.output_names.size());
  d.insert(d.end(), obs_.begin() + 2, reactions);
  if (cm.m > 0 || !cm.loads.empty()) dyn.forward(t, q, v, qdot_.data(), a_.data(), lambda_.data());
  if (cm.m > 0) {
    dyn.last_constraints(C_.data(), Cdot_.data());
    d.insert(d.end(), lambda_.begin(), lambda_.end());
    d.push_back(max_abs(C_));
    d.push_back(max_abs(Cdot_));
    for (size_t r = 0; r < cm.reaction_names.size(); ++r)
      d.push_back(lambda_[cm.reaction_constraints[r]] * reactions[static_cast<long>(r)]);
  }
  for (const LoadColumn& load : cm.loads) d.push_back(load_value(load));
}

}  // namespace lagrange
