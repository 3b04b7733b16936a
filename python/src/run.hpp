#pragma once
// lagrange.Run: a simulated trajectory, its columns as numpy views of the C++ buffer.

#include <pybind11/pybind11.h>

#include "lagrange/simulation.hpp"

namespace lagrange::python {

/// What Model.simulate returns: the trajectory as the library produced it (never copied).
struct Run {
  Trajectory trajectory;
};

/// Binds lagrange.Run.
void bind_run(pybind11::module_& m);

}  // namespace lagrange::python
