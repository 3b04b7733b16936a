#include "simulation/row_writer.hpp"

#include "simulation/max_abs.hpp"

namespace lagrange {

RowWriter::RowWriter(const CompiledModel& cm)
    : obs_(cm.observables.num_outputs()),
      qdot_(cm.nq),
      a_(cm.nv),
      lambda_(cm.m),
      C_(cm.m),
      Cdot_(cm.m) {}

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
  const auto reactions = obs_.end() - static_cast<long>(cm.reaction_names.size());
  d.insert(d.end(), obs_.begin() + 2, reactions);
  if (cm.m > 0) {
    dyn.forward(t, q, v, qdot_.data(), a_.data(), lambda_.data());
    dyn.last_constraints(C_.data(), Cdot_.data());
    d.insert(d.end(), lambda_.begin(), lambda_.end());
    d.push_back(max_abs(C_));
    d.push_back(max_abs(Cdot_));
    for (size_t r = 0; r < cm.reaction_names.size(); ++r)
      d.push_back(lambda_[cm.reaction_constraints[r]] * reactions[static_cast<long>(r)]);
  }
}

}  // namespace lagrange
