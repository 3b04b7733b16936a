#pragma once
// Test helper: an example's model, equations, tapes and workspace, ready for optimize().

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/optimize.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"
#include "support/test_paths.hpp"

namespace lagrange::testing {

/// examples/optimal/NAME, or tests/optimize/data/NAME for "data/NAME".
inline std::string path(const std::string& name) {
  const std::string root = LAGRANGE_SOURCE_DIR;
  if (name.rfind("data/", 0) == 0) return root + "/tests/optimize/" + name;
  return root + "/examples/optimal/" + name;
}

/// Column `name` of a trajectory (a failed expectation when there is none).
inline std::vector<double> column(const Trajectory& t, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  EXPECT_NE(it, t.columns.end()) << name;
  const size_t c = static_cast<size_t>(it - t.columns.begin()), n = t.columns.size();
  std::vector<double> out;
  if (it == t.columns.end()) return out;
  for (size_t r = 0; r < t.rows(); ++r) out.push_back(t.data[r * n + c]);
  return out;
}

struct OptimalProblem {
  std::unique_ptr<Model> model;
  Equations eq;
  std::shared_ptr<const CompiledModel> cm;
  std::unique_ptr<Dynamics> dyn;

  explicit OptimalProblem(const std::string& example, const ParameterOverrides& sets = {})
      : OptimalProblem(read_model_file(path(example), sets)) {}
  explicit OptimalProblem(Model m)
      : model(std::make_unique<Model>(std::move(m))),
        eq(derive(*model)),
        cm(compile(eq)),
        dyn(std::make_unique<Dynamics>(cm, cm->parameter_defaults)) {
    dyn->set_baumgarte(baumgarte_rate(model->stabilization, model->simulate.integrator));
  }
  const OptimalControlSpec& spec() const { return *model->optimal_control; }
  OptimizeResult solve(int intervals = 0, int degree = 0) {
    OptimizeOptions o;
    o.intervals = intervals;
    o.degree = degree;
    return optimize(eq, cm, *dyn, spec(), cm->q0, cm->v0, o);
  }
};

}  // namespace lagrange::testing
