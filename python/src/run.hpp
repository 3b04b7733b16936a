#pragma once
// lagrange.Run: a simulated trajectory, its columns as numpy views of the C++ buffer.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "cli/prepare.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange::python {

/// What Model.simulate returns: the trajectory as the library produced it (never copied), and
/// the prepared model and run facts its HTML report shows.
struct Run {
  Trajectory trajectory;
  std::shared_ptr<const cli::Prepared> prepared;
  std::string integrator;
  double wall_seconds = -1;
};

/// Binds lagrange.Run.
void bind_run(pybind11::module_& m);

}  // namespace lagrange::python
