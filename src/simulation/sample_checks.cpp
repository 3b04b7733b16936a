#include "simulation/sample_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lagrange/error.hpp"

namespace lagrange {

SampleChecks::SampleChecks(const CompiledModel& cm, const std::vector<std::string>& columns)
    : cm_(cm),
      columns_(columns),
      cautions_(cm, StopConditions::Kind::Warn),
      caution_g_(cautions_.size()),
      cautioned_(cautions_.size(), false) {
  kinetic_ = 1 + cm.nq + cm.nv;  // t, q, v, then kinetic, potential, energy, outputs
  outputs_end_ = kinetic_ + 3 + cm.output_names.size();
}

void SampleChecks::state(double t, const double* y) const {
  for (size_t i = 0; i < cm_.nq + cm_.nv; ++i)
    if (!std::isfinite(y[i]))
      throw SimulationError(
          t,
          fmt::format("the state is not finite ({} = {})",
                      i < cm_.nq ? cm_.coordinate_names[i] : cm_.velocity_names[i - cm_.nq], y[i]));
}

// docs/theory.md §8.2, "Samples checked before a run is called complete".
void SampleChecks::row(double t, const double* row) {
  auto not_finite = [&](size_t c) {
    throw SimulationError(t,
                          fmt::format("the {} '{}' is not finite ({}) at a finite state: the "
                                      "equations have no value there (a singular mass matrix "
                                      "or a division by zero)",
                                      c < kinetic_ + 3 ? "energy" : "column", columns_[c], row[c]));
  };
  for (size_t c = kinetic_; c < kinetic_ + 3; ++c)
    if (!std::isfinite(row[c])) not_finite(c);
  for (size_t c = outputs_end_; c < columns_.size(); ++c)
    if (!std::isfinite(row[c])) not_finite(c);
  const double T = row[kinetic_], U = row[kinetic_ + 1], E = row[kinetic_ + 2];
  if (!started_) {
    started_ = true;
    t0_ = t_prev_ = t;
    e0_ = E;
    scale_ = std::abs(T) + std::abs(U);
    scale_at_ = t;
    return;
  }
  const double size = std::abs(T) + std::abs(U);
  if (size > scale_) scale_ = size, scale_at_ = t;
  if (cm_.conservative && std::abs(E - e0_) > 0.5 * scale_)
    throw SimulationError(
        t, fmt::format("the energy T + U of this conservative model (no forces, dampers, "
                       "torques, inputs or time dependence) went from {:.6g} at t = {:.6g} to "
                       "{:.6g} between the samples at t = {:.6g} and {:.6g}, more than half the "
                       "largest T + |U| so far ({:.6g} at t = {:.6g}): the integrator stepped "
                       "across a singularity of the equations (a 1/r potential at r = 0, say) or "
                       "is unstable at this step size",
                       e0_, t0_, E, t_prev_, t, scale_, scale_at_));
  t_prev_ = t;
}

void SampleChecks::append_row(RowWriter& rows, Dynamics& dyn, double t, const double* y,
                              Trajectory& traj, const std::function<void(const double*)>& also) {
  const size_t width = traj.columns.size();
  rows.append(dyn, t, y, y + cm_.nq, traj);
  try {
    const double* written = traj.data.data() + traj.data.size() - width;
    if (also) also(written);
    row(t, written);
  } catch (const SimulationError&) {
    traj.data.resize(traj.data.size() - width);
    throw;
  }
  warn(traj.data.data() + traj.data.size() - width, dyn.parameters().data(), t, traj);
}

// CompiledModel::warn_when, the conditions the model itself declares: once per condition and run.
void SampleChecks::warn(const double* row, const double* parameters, double t, Trajectory& traj) {
  if (cautions_.empty()) return;
  cautions_.evaluate(row, parameters, caution_g_.data());
  for (size_t i = 0; i < cautions_.size(); ++i)
    if (caution_g_[i] > 0 && !cautioned_[i]) {
      cautioned_[i] = true;
      const StopSpec& c = cautions_.spec(i);
      traj.warnings.push_back(
          fmt::format("from t = {:.6g}: {} ({}, {})", t, c.name, c.text, c.loc.str()));
    }
}

}  // namespace lagrange
