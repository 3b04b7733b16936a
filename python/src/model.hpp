#pragma once
// lagrange.Model and lagrange.Equations: a model prepared exactly as `lagrange simulate` prepares
// it (src/cli/prepare.hpp), its equations, runs and forward dynamics.

#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/prepare.hpp"
#include "cli/sweep_inputs.hpp"

namespace lagrange::python {

/// A loaded model: where it came from (for pickling) and what prepare_source() made of it. The
/// Prepared part is never changed after loading, so that runs on other threads can share its
/// compiled model; `forward` uses its Dynamics with the GIL held.
struct PyModel {
  cli::ModelSource source;
  ParameterOverrides overrides;
  std::string dynamics;
  std::vector<std::pair<std::string, double>> initial;  ///< coordinates and NAME_dot velocities
  std::shared_ptr<cli::Prepared> prepared;
  std::vector<double> qdot;  ///< forward's scratch (used with the GIL held)
  /// lagrange.sweep's cases' inputs from one read, by varied names and settings (a cache, used
  /// with the GIL held: a worker process reads the model for its first chunk only).
  mutable std::map<std::string, std::shared_ptr<const cli::StudyReplay>> replays;
};

/// What cvode:jacobian's message tells a user of a model in the recursive form to do.
inline constexpr const char* kLagrangianHint = "load the model with dynamics=\"lagrangian\"";

/// Reads, derives, compiles and checks a model (holding the GIL: GiNaC is not thread-safe).
PyModel load_model(cli::ModelSource source, ParameterOverrides overrides,
                   const std::string& dynamics,
                   std::vector<std::pair<std::string, double>> initial);

/// Binds lagrange.Model, lagrange.Equations and the functions load and loads.
void bind_model(pybind11::module_& m);

}  // namespace lagrange::python
