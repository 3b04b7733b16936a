#pragma once
// Model.linearize and Model.trim: the library's exact linearisation and trim (docs/theory.md §5)
// on a loaded model, as `lagrange linearize` and `lagrange trim` compute them.

#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "model.hpp"

namespace lagrange::python {

/// What `linearize` trims first, as `lagrange linearize --at-trim --free … --fix … --steady …`.
struct TrimFirst {
  bool at_trim = false;
  std::vector<std::string> free, fix, steady;
  double tol = 0.0;
};

/// A, B, C, D (numpy), names, modes and the basis at (q, v) (default: the model's consistent
/// initial state) with parameters and model inputs at `values`, after a trim when `first` asks
/// for one (its result as `trim`), as a types.SimpleNamespace; `discrete` > 0 gives the
/// zero-order hold.
pybind11::object linearize_model(const PyModel& m, std::optional<pybind11::object> q,
                                 std::optional<pybind11::object> v,
                                 const std::vector<std::string>& inputs,
                                 const std::vector<std::string>& outputs,
                                 std::optional<double> discrete, double t,
                                 const std::map<std::string, double>& values,
                                 const TrimFirst& first);

/// An equilibrium or, with `steady` rates held at their values in v (default: the initial
/// rates), a steady state from q, varying `free` minus `fix` as `lagrange trim` does: q, v,
/// iterations, residual, drift and pseudo_transient as a types.SimpleNamespace.
pybind11::object trim_model(const PyModel& m, std::optional<pybind11::object> q,
                            const std::vector<std::string>& free,
                            const std::vector<std::string>& fix, double tol, int max_iterations,
                            double t, const std::vector<std::string>& steady,
                            std::optional<pybind11::object> v);

/// The exact Jacobians at (q, v) (default: the initial state): ∂a/∂(q, v, inputs), ∂q̇/∂(q, v),
/// G, ∂C/∂q, and the implicit form's K and ∂Φ/∂(q, v, inputs) (dense numpy).
pybind11::object jacobian_model(const PyModel& m, std::optional<pybind11::object> q,
                                std::optional<pybind11::object> v,
                                const std::vector<std::string>& inputs, double t);

}  // namespace lagrange::python
