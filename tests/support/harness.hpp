#pragma once
// Test helpers: load an example, look up symbols by name, run a simulation.

#include <ginac/ginac.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <string>

#include "support/test_paths.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/model.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange::testing {

using lagrange::test::example_path;

/// Symbol of a parameter, coordinate (q, or v with suffix "_dot", a with "_ddot") or input.
inline GiNaC::symbol sym(const Model& m, const std::string& name) {
  for (const auto& p : m.parameters)
    if (p.name == name) return p.sym;
  for (const auto& c : m.coordinates) {
    if (c.name == name) return c.q;
    if (c.name + "_dot" == name) return c.v;
    if (c.name + "_ddot" == name) return c.a;
  }
  for (const auto& u : m.inputs)
    if (u.name == name) return u.u;
  throw std::invalid_argument("no symbol " + name);
}

/// True when a − b normalises to zero (symbolic equality of canonical forms).
inline bool same(const GiNaC::ex& a, const GiNaC::ex& b) {
  return simplify(a - b).is_zero();
}

/// A model with everything needed to simulate it.
struct Loaded {
  std::unique_ptr<Model> model;
  std::shared_ptr<const CompiledModel> compiled;
  std::unique_ptr<Dynamics> dynamics;

  /// Simulation options from the model file's `simulate:` and `stabilization:` keys.
  SimulationOptions options() const {
    SimulationOptions so;
    so.t_end = model->simulate.t_end;
    so.output_step = model->simulate.output_step;
    so.integrator.method = model->simulate.integrator;
    so.integrator.rtol = model->simulate.rtol;
    so.integrator.atol = model->simulate.atol;
    so.integrator.step = model->simulate.step;
    so.project = model->stabilization.project;
    return so;
  }
  Trajectory run(const SimulationOptions& so) {
    return simulate(*dynamics, so, compiled->q0, compiled->v0);
  }
};

inline Loaded load_model(std::unique_ptr<Model> model) {
  Loaded l;
  l.model = std::move(model);
  l.compiled = compile(derive(*l.model));
  l.dynamics = std::make_unique<Dynamics>(l.compiled, l.compiled->parameter_defaults);
  l.dynamics->set_baumgarte(baumgarte_rate(l.model->stabilization, l.model->simulate.integrator));
  return l;
}

/// The model's own settings with tight tolerances (rtol 1e-12, atol 1e-14), t_end and step.
inline SimulationOptions tight(const Loaded& sys, double t_end, double step) {
  SimulationOptions so = sys.options();
  so.t_end = t_end;
  so.output_step = step;
  so.integrator.rtol = 1e-12;
  so.integrator.atol = 1e-14;
  return so;
}

/// A free body's rotation matrix R at row r (columns <body>.R11 … .R33).
inline Eigen::Matrix3d rotation_at(const Trajectory& tr, size_t r, const std::string& body) {
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      R(i, j) = tr.at(r, body + ".R" + std::to_string(i + 1) + std::to_string(j + 1));
  return R;
}

/// A free body's body-frame angular velocity at row r.
inline Eigen::Vector3d omega_at(const Trajectory& tr, size_t r, const std::string& body) {
  return {tr.at(r, body + ".wx"), tr.at(r, body + ".wy"), tr.at(r, body + ".wz")};
}

/// File names of every bundled example (examples/*.yaml), sorted.
inline std::vector<std::string> example_files() {
  std::vector<std::string> names;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(LAGRANGE_SOURCE_DIR) + "/examples"))
    if (e.path().extension() == ".yaml") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// example_files() and then the robot descriptions beside them (`robots/<name>.urdf`), sorted.
inline std::vector<std::string> model_files() {
  std::vector<std::string> names = example_files(), robots;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots"))
    if (e.path().extension() == ".urdf") robots.push_back("robots/" + e.path().filename().string());
  std::sort(robots.begin(), robots.end());
  names.insert(names.end(), robots.begin(), robots.end());
  return names;
}

/// A test-name-safe label of a model file name ("robots/ur5.urdf" → "robots_ur5").
inline std::string model_label(const std::string& file) {
  std::string n = file.substr(0, file.rfind('.'));
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

inline Loaded load_example(const std::string& name) {
  return load_model(std::make_unique<Model>(read_model_file(example_path(name))));
}

inline Loaded load_string(const std::string& yaml) {
  return load_model(std::make_unique<Model>(read_model_string(yaml, "<test>")));
}

}  // namespace lagrange::testing
