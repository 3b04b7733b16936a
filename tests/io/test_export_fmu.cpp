// `export --fmu` (docs/fmu.md) driven by a small FMI 2.0 importer (fmu_importer.hpp): Co-Simulation
// against `lagrange simulate`, closed forms and energy conservation; Model Exchange derivatives
// against Dynamics::forward; parameters, inputs, misuse and the binary's dependencies.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "fmu_importer.hpp"
#include "hardening/cli_runner.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;
using testing::FmuImporter;
using testing::FmuLog;

// A model, its FMU and the importer over it, made once per model and process, in a directory of
// this process's own (ctest runs the tests as parallel processes) removed at exit.
struct Exported {
  testing::Loaded sys;
  FmuOptions options;
  fs::path dir;
  std::unique_ptr<FmuImporter> fmu;
  ~Exported() {
    fmu.reset();  // dlclose before the binary's directory goes
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

Exported& exported(const std::string& label, testing::Loaded (*load)()) {
  static std::map<std::string, std::unique_ptr<Exported>> cache;
  auto& slot = cache[label];
  if (!slot) {
    slot = std::make_unique<Exported>();
    slot->sys = load();
    slot->options = fmu_options(*slot->sys.model);
    slot->options.equations = "(equations)";
    slot->dir = fs::temp_directory_path() /
                ("lagrange_fmu_test_" + label + "_" + std::to_string(::getpid()));
    fs::remove_all(slot->dir);
    fs::create_directories(slot->dir);
    export_fmu(*slot->sys.compiled, slot->options, (slot->dir / "model.fmu").string());
    slot->fmu = std::make_unique<FmuImporter>(slot->dir / "model.fmu", slot->dir / "unzipped");
  }
  return *slot;
}

Exported& pendulum() {
  return exported("pendulum", [] { return testing::load_example("pendulum.yaml"); });
}
Exported& cartesian() {
  return exported("cartesian", [] { return testing::load_example("cartesian_pendulum.yaml"); });
}
// A mass on a spring pushed by an external force F: x = F/k + (x0 − F/k) cos(√(k/m) t) while F
// is held.
Exported& driven() {
  return exported("driven", [] {
    return testing::load_string(
        "name: driven mass\nparameters: {m: 2.0, k: 8.0}\n"
        "coordinates:\n  x: {initial: 0.1, rate: 0.0}\n"
        "inputs:\n  F: {value: 0.5, external: true}\n"
        "points:\n  p: [x, 0, 0]\nparticles:\n  - {point: p, mass: m}\n"
        "potential: k/2*x^2\ngeneralized_forces: {x: F}\n"
        "simulate: {t_end: 2, output_step: 0.01, rtol: 1e-10, atol: 1e-12}\n");
  });
}

// examples/fmu/panda_torques.yaml: the Franka Panda's URDF with its seven joint torques as external
// inputs tau1 … tau7, in the articulated-body form `lagrange export` takes for a joint tree
// (docs/theory.md §4.9; the Lagrangian form's C takes the compiler seconds longer).
Exported& panda() {
  return exported("panda", [] {
    auto model =
        std::make_unique<Model>(read_model_file(testing::example_path("fmu/panda_torques.yaml")));
    testing::Loaded l;
    l.compiled = compile(derive(*model, Formulation::Recursive));
    l.model = std::move(model);
    return l;
  });
}

// An initialised Co-Simulation instance at t = 0 (parameters set before initialisation).
fmi2Component start_cs(FmuImporter& f, FmuLog& log,
                       const std::map<std::string, double>& parameters = {}) {
  fmi2Component c = f.make(fmi2CoSimulation, log);
  EXPECT_NE(c, nullptr);
  EXPECT_EQ(f.setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
  for (const auto& [name, value] : parameters) EXPECT_EQ(f.set(c, name, value), fmi2OK) << name;
  EXPECT_EQ(f.enter_init(c), fmi2OK);
  EXPECT_EQ(f.exit_init(c), fmi2OK);
  return c;
}

// Steps of `h` up to `t_end`, recording `columns` after each (row r at t = (r + 1) h).
std::vector<std::vector<double>> run_cs(FmuImporter& f, fmi2Component c, double h, int steps,
                                        const std::vector<std::string>& columns) {
  std::vector<std::vector<double>> rows;
  for (int i = 0; i < steps; ++i) {
    EXPECT_EQ(f.do_step(c, i * h, h, fmi2True), fmi2OK) << "step " << i;
    std::vector<double> row;
    for (const auto& name : columns) row.push_back(f.get(c, name));
    rows.push_back(row);
  }
  return rows;
}

// The FMU's Co-Simulation against `lagrange simulate` (dop853, the model's tolerances) on the
// output grid of 0.01 up to `steps`, and T + U conserved.
void expect_matches_simulate(Exported& e, const std::vector<std::string>& columns, double tol,
                             int steps = 200) {
  SimulationOptions so = e.sys.options();
  so.t_end = 0.01 * steps;
  so.output_step = 0.01;
  const Trajectory tr = e.sys.run(so);
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log);
  std::vector<std::string> all = columns;
  all.push_back("energy");
  const auto rows = run_cs(*e.fmu, c, 0.01, steps, all);
  const double e0 = tr.at(0, "energy");
  for (size_t r = 0; r < rows.size(); ++r) {
    for (size_t j = 0; j < columns.size(); ++j)
      ASSERT_NEAR(rows[r][j], tr.at(r + 1, columns[j]), tol)
          << columns[j] << " at t = " << tr.at(r + 1, "t");
    ASSERT_NEAR(rows[r].back(), e0, 1e-8 * (1.0 + std::abs(e0))) << "energy at row " << r;
  }
  e.fmu->free_instance(c);
  EXPECT_TRUE(log.messages.empty()) << log.messages.front();
}

TEST(ExportFmu, PendulumCoSimulationMatchesSimulate) {
  expect_matches_simulate(pendulum(), {"theta", "theta_dot", "x", "y"}, 1e-7);
}

// The constrained Cartesian pendulum: positions and the rod's multiplier as simulate gives them.
// With Baumgarte's term off, a loose rtol and long communication steps, only the projection after
// each step keeps C = (x² + y² − l²)/2 within its threshold max(1e-11, atol) (without it, with
// `stabilization: {project: false}`, max |C| is 1e-5 here).
TEST(ExportFmu, CartesianPendulumStaysOnItsConstraint) {
  Exported& e = cartesian();
  expect_matches_simulate(e, {"x", "y", "x_dot", "rod"}, 1e-6);
  FmuLog log;
  fmi2Component c = start_cs(
      *e.fmu, log, {{"fmu.baumgarte_alpha", 0.0}, {"fmu.rtol", 1e-4}, {"fmu.atol", 1e-12}});
  for (const auto& row : run_cs(*e.fmu, c, 0.5, 8, {"x", "y"}))
    EXPECT_LE(std::abs((row[0] * row[0] + row[1] * row[1] - 1.0) / 2), 2e-11);
  e.fmu->free_instance(c);
}

// The heavy top, a free body in SO(3) held at a pivot: the FMU's projection (all of q, then R's
// polar factor) ends where the engine's (tangent coordinates) does, within the tolerances; R stays
// orthonormal and the pivot at the origin.
TEST(ExportFmu, HeavyTopKeepsItsRotationAndPivot) {
  Exported& e = exported("heavy_top", [] { return testing::load_example("heavy_top.yaml"); });
  expect_matches_simulate(e, {"top.x", "top.R13", "axis.z", "top.wz", "pivot.z"}, 1e-6, 30);
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log);
  ASSERT_EQ(e.fmu->do_step(c, 0.0, 0.3, fmi2True), fmi2OK);
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      R(i, j) = e.fmu->get(c, "top.R" + std::to_string(i + 1) + std::to_string(j + 1));
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 2e-11);
  const Eigen::Vector3d r{e.fmu->get(c, "top.x"), e.fmu->get(c, "top.y"), e.fmu->get(c, "top.z")};
  EXPECT_LE((r + R * Eigen::Vector3d(0, 0, -0.1)).norm(), 2e-11);  // C = r + R p
  e.fmu->free_instance(c);
}

// Model Exchange: fmi2GetDerivatives at a perturbed state equals Dynamics::forward with the FMU's
// Baumgarte rate, to 1e-12 of the largest value (two implementations of the same KKT solve).
void expect_derivatives_match(Exported& e, double t) {
  const CompiledModel& cm = *e.sys.compiled;
  std::vector<double> x(cm.q0);
  x.insert(x.end(), cm.v0.begin(), cm.v0.end());
  for (size_t i = 0; i < x.size(); ++i) x[i] += 0.05 * std::sin(1.0 + static_cast<double>(i));
  std::vector<double> want(x.size()), lambda(cm.m);
  e.sys.dynamics->set_baumgarte(e.options.alpha);
  e.sys.dynamics->forward(t, x.data(), x.data() + cm.nq, want.data(), want.data() + cm.nq,
                          lambda.data());
  FmuImporter& f = *e.fmu;
  FmuLog log;
  fmi2Component c = f.make(fmi2ModelExchange, log);
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(f.setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
  ASSERT_EQ(f.enter_init(c), fmi2OK);
  ASSERT_EQ(f.exit_init(c), fmi2OK);
  fmi2EventInfo info{};
  ASSERT_EQ(f.new_discrete_states(c, &info), fmi2OK);
  ASSERT_EQ(f.enter_continuous(c), fmi2OK);
  ASSERT_EQ(f.set_time(c, t), fmi2OK);
  ASSERT_EQ(f.set_states(c, x.data(), x.size()), fmi2OK);
  std::vector<double> got(x.size());
  ASSERT_EQ(f.get_derivatives(c, got.data(), got.size()), fmi2OK);
  double scale = 1.0, worst = 0.0;
  for (size_t i = 0; i < got.size(); ++i) {
    scale = std::max(scale, std::abs(want[i]));
    worst = std::max(worst, std::abs(got[i] - want[i]));
  }
  EXPECT_LE(worst, 1e-12 * scale);
  for (size_t r = 0; r < cm.m; ++r)
    EXPECT_NEAR(f.get(c, cm.constraint_names[r]), lambda[r], 1e-12 * (1 + std::abs(lambda[r])));
  f.free_instance(c);
}

TEST(ExportFmu, ModelExchangeDerivativesMatchTheEngine) {
  expect_derivatives_match(cartesian(), 0.3);
  expect_derivatives_match(exported("crane", [] { return testing::load_example("crane.yaml"); }),
                           1.3);
  expect_derivatives_match(
      exported("heavy_top", [] { return testing::load_example("heavy_top.yaml"); }), 0.2);
}

// fmi2SetReal of a parameter before initialisation gives the run `--set` gives.
TEST(ExportFmu, ParameterSetLikeSet) {
  Exported& e = pendulum();
  const CompiledModel& cm = *e.sys.compiled;
  std::vector<double> p = cm.parameter_defaults;
  const size_t l =
      static_cast<size_t>(std::find(cm.parameter_names.begin(), cm.parameter_names.end(), "l") -
                          cm.parameter_names.begin());
  ASSERT_LT(l, p.size());
  p[l] = 2.0;
  Dynamics longer(e.sys.compiled, p);
  SimulationOptions so = e.sys.options();
  so.t_end = 1.0;
  so.output_step = 0.1;
  const Trajectory tr = simulate(longer, so, cm.q0, cm.v0);
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log, {{"l", 2.0}});
  const auto rows = run_cs(*e.fmu, c, 0.1, 10, {"theta", "y"});
  EXPECT_NEAR(rows.back()[0], tr.at(10, "theta"), 1e-7);
  EXPECT_NEAR(rows.back()[1], tr.at(10, "y"), 1e-7);
  e.fmu->free_instance(c);
}

// A tunable parameter set between steps acts from the next step: the pendulum's l changed from 1
// to 2 at t = 0.5 gives simulate's run with l = 1 up to 0.5, continued with l = 2 from its state.
TEST(ExportFmu, TunableParameterActsFromTheNextStep) {
  Exported& e = pendulum();
  EXPECT_EQ(e.fmu->variables.at("l").causality, "parameter");
  const CompiledModel& cm = *e.sys.compiled;
  SimulationOptions so = e.sys.options();
  so.t_end = 0.5;
  so.output_step = 0.1;
  const Trajectory first = e.sys.run(so);
  std::vector<double> p = cm.parameter_defaults;
  const auto l = std::find(cm.parameter_names.begin(), cm.parameter_names.end(), "l");
  ASSERT_NE(l, cm.parameter_names.end());
  p[static_cast<size_t>(l - cm.parameter_names.begin())] = 2.0;
  Dynamics longer(e.sys.compiled, p);
  so.t0 = 0.5;
  so.t_end = 1.0;
  const Trajectory second =
      simulate(longer, so, {first.at(5, "theta")}, {first.at(5, "theta_dot")});
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log);
  run_cs(*e.fmu, c, 0.1, 5, {});
  EXPECT_NEAR(e.fmu->get(c, "theta"), first.at(5, "theta"), 1e-8);
  ASSERT_EQ(e.fmu->set(c, "l", 2.0), fmi2OK);
  for (int i = 5; i < 10; ++i) ASSERT_EQ(e.fmu->do_step(c, i * 0.1, 0.1, fmi2True), fmi2OK);
  EXPECT_NEAR(e.fmu->get(c, "theta"), second.at(5, "theta"), 1e-7);
  EXPECT_NEAR(e.fmu->get(c, "theta_dot"), second.at(5, "theta_dot"), 1e-7);
  e.fmu->free_instance(c);
  // Model Exchange: set in event mode, the derivative is −(g/l) sin θ with the new l; in
  // continuous-time mode a parameter cannot be set.
  fmi2Component m = e.fmu->make(fmi2ModelExchange, log);
  ASSERT_EQ(e.fmu->enter_init(m), fmi2OK);
  ASSERT_EQ(e.fmu->exit_init(m), fmi2OK);
  ASSERT_EQ(e.fmu->set(m, "l", 2.0), fmi2OK);
  fmi2EventInfo info{};
  ASSERT_EQ(e.fmu->new_discrete_states(m, &info), fmi2OK);
  ASSERT_EQ(e.fmu->enter_continuous(m), fmi2OK);
  double dx[2];
  ASSERT_EQ(e.fmu->get_derivatives(m, dx, 2), fmi2OK);
  EXPECT_NEAR(dx[1], -9.81 / 2.0 * std::sin(cm.q0[0]), 1e-14);
  EXPECT_TRUE(log.messages.empty()) << log.messages.front();
  EXPECT_EQ(e.fmu->set(m, "l", 3.0), fmi2Error);
  EXPECT_NE(log.messages.back().find("continuous-time mode"), std::string::npos);
  e.fmu->free_instance(m);
}

// An external input follows its declared value until set, then is held between steps.
TEST(ExportFmu, ExternalInputHeldBetweenSteps) {
  Exported& e = driven();
  FmuImporter& f = *e.fmu;
  EXPECT_EQ(f.variables.at("F").causality, "input");
  EXPECT_EQ(f.variables.at("F").start, 0.5);
  FmuLog log;
  fmi2Component c = start_cs(f, log);
  const double w = 2.0;  // √(k/m)
  auto x_at = [&](double t, double x0, double v0, double F) {
    return F / 8.0 + (x0 - F / 8.0) * std::cos(w * t) + v0 / w * std::sin(w * t);
  };
  const auto first = run_cs(f, c, 0.1, 5, {"x", "x_dot"});
  EXPECT_NEAR(first.back()[0], x_at(0.5, 0.1, 0.0, 0.5), 1e-8);
  ASSERT_EQ(f.set(c, "F", 1.5), fmi2OK);
  EXPECT_EQ(f.get(c, "F"), 1.5);
  double x = first.back()[0], v = first.back()[1];
  for (int i = 5; i < 10; ++i) ASSERT_EQ(f.do_step(c, i * 0.1, 0.1, fmi2True), fmi2OK);
  EXPECT_NEAR(f.get(c, "x"), x_at(0.5, x, v, 1.5), 1e-8);
  // A NaN input is refused with a message, and the instance then refuses to step.
  EXPECT_EQ(f.set(c, "F", NAN), fmi2Error);
  ASSERT_FALSE(log.messages.empty());
  EXPECT_NE(log.messages.back().find("finite"), std::string::npos) << log.messages.back();
  EXPECT_EQ(f.do_step(c, 1.0, 0.1, fmi2True), fmi2Error);
  EXPECT_NE(log.messages.back().find("earlier call failed"), std::string::npos);
  EXPECT_EQ(f.reset(c), fmi2OK);
  f.free_instance(c);
}

// Calls out of order and a foreign GUID are refused with a message, never a crash.
TEST(ExportFmu, MisuseIsAnErrorWithAMessage) {
  FmuImporter& f = *pendulum().fmu;
  FmuLog log;
  EXPECT_EQ(f.make(fmi2CoSimulation, log, "x", "{not-the-guid}"), nullptr);
  ASSERT_EQ(log.messages.size(), 1u);
  EXPECT_NE(log.messages[0].find("GUID"), std::string::npos);
  fmi2Component c = f.make(fmi2CoSimulation, log);
  EXPECT_EQ(f.do_step(c, 0.0, 0.1, fmi2True), fmi2Error);
  EXPECT_NE(log.messages.back().find("not allowed in instantiated"), std::string::npos)
      << log.messages.back();
  EXPECT_EQ(f.reset(c), fmi2OK);
  const fmi2ValueReference unknown = 99999;
  const double one = 1.0;
  EXPECT_EQ(f.set_real(c, &unknown, 1, &one), fmi2Error);
  EXPECT_NE(log.messages.back().find("99999"), std::string::npos) << log.messages.back();
  f.free_instance(c);
  fmi2Component c2 = start_cs(f, log);
  ASSERT_EQ(f.terminate(c2), fmi2OK);
  EXPECT_EQ(f.set(c2, "l", 3.0), fmi2Error);  // a parameter after fmi2Terminate
  EXPECT_NE(log.messages.back().find("after fmi2Terminate"), std::string::npos)
      << log.messages.back();
  EXPECT_EQ(f.do_step(c2, 0.0, 0.1, fmi2True), fmi2Error);
  f.free_instance(c2);
  // A massless bob: M = 0 is singular, which initialisation reports instead of dividing by it.
  fmi2Component c3 = f.make(fmi2CoSimulation, log);
  ASSERT_EQ(f.set(c3, "m", 0.0), fmi2OK);
  ASSERT_EQ(f.enter_init(c3), fmi2OK);
  EXPECT_EQ(f.exit_init(c3), fmi2Error);
  EXPECT_NE(log.messages.back().find("singular mass matrix"), std::string::npos)
      << log.messages.back();
  EXPECT_EQ(f.do_step(c3, 0.0, 0.1, fmi2True), fmi2Error);
  f.free_instance(c3);
}

// Two instances in one process, stepped in turn, give what each gives alone; fmi2GetFMUstate and
// fmi2SetFMUstate replay a step bit for bit.
TEST(ExportFmu, InstancesAreIndependentAndStatesRestore) {
  FmuImporter& f = *pendulum().fmu;
  FmuLog log;
  fmi2Component alone = start_cs(f, log, {{"l", 2.0}});
  const auto want = run_cs(f, alone, 0.1, 10, {"theta"});
  f.free_instance(alone);
  fmi2Component a = start_cs(f, log), b = start_cs(f, log, {{"l", 2.0}});
  for (int i = 0; i < 10; ++i) {
    ASSERT_EQ(f.do_step(a, i * 0.1, 0.1, fmi2True), fmi2OK);
    ASSERT_EQ(f.do_step(b, i * 0.1, 0.1, fmi2True), fmi2OK);
    EXPECT_EQ(f.get(b, "theta"), want[i][0]);
    EXPECT_NE(f.get(a, "theta"), want[i][0]);
  }
  fmi2FMUstate saved = nullptr;
  ASSERT_EQ(f.get_state(a, &saved), fmi2OK);
  ASSERT_EQ(f.do_step(a, 1.0, 0.5, fmi2True), fmi2OK);
  const double once = f.get(a, "theta");
  ASSERT_EQ(f.set_state(a, saved), fmi2OK);
  ASSERT_EQ(f.do_step(a, 1.0, 0.5, fmi2True), fmi2OK);
  EXPECT_EQ(f.get(a, "theta"), once);
  EXPECT_EQ(f.free_state(a, &saved), fmi2OK);
  f.free_instance(a);
  f.free_instance(b);
  EXPECT_TRUE(log.messages.empty());
}

// A ball dropped from h0 = 2 m: z = h0 − g t²/2 reaches the ground at t* = √(2 h0 / g). `ground`
// reads an output, `fast` (never true here) a velocity column.
Exported& ball() {
  return exported("ball", [] {
    return testing::load_string(
        "name: falling ball\nparameters: {m: 1.0, g: 9.81, h0: 2.0}\n"
        "coordinates:\n  z: {initial: h0, rate: 0.0}\n"
        "points:\n  p: [0, 0, z]\nparticles:\n  - {point: p, mass: m}\ngravity: [0, 0, -g]\n"
        "outputs: {height: z}\n"
        "stop_when:\n  fast: z_dot < -100\n  ground: height < 0\n"
        "simulate: {t_end: 2, output_step: 0.01, rtol: 1e-10, atol: 1e-12}\n");
  });
}
const double kGroundTime = std::sqrt(2.0 * 2.0 / 9.81);

// Co-Simulation steps of `h` until fmi2DoStep returns fmi2Discard (docs/fmu.md, "Stop
// conditions"); the time it reports by fmi2LastSuccessfulTime and fmi2Terminated.
double run_until_stopped(FmuImporter& f, fmi2Component c, double h, int max_steps) {
  for (int i = 0; i < max_steps; ++i) {
    const fmi2Status status = f.do_step(c, i * h, h, fmi2True);
    if (status == fmi2OK) continue;
    EXPECT_EQ(status, fmi2Discard) << "step " << i;
    fmi2Boolean terminated = fmi2False;
    EXPECT_EQ(f.get_boolean_status(c, fmi2Terminated, &terminated), fmi2OK);
    EXPECT_EQ(terminated, fmi2True);
    double t = NAN;
    EXPECT_EQ(f.get_real_status(c, fmi2LastSuccessfulTime, &t), fmi2OK);
    EXPECT_GT(t, i * h);
    EXPECT_LE(t, (i + 1) * h);
    EXPECT_EQ(f.do_step(c, t, h, fmi2True), fmi2Discard);  // it cannot go further
    return t;
  }
  ADD_FAILURE() << "no stop within " << max_steps << " steps";
  return NAN;
}

// fmi2DoStep ends where `ground` becomes true: at simulate's stop time and at the closed form,
// on the ground; the steps before it are whole.
TEST(ExportFmu, StopWhenEndsTheStepWhereSimulateStops) {
  Exported& e = ball();
  EXPECT_EQ(e.fmu->event_indicators, 2u);
  const Trajectory tr = e.sys.run(e.sys.options());
  ASSERT_EQ(tr.stopped_by, "ground");
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log);
  const double t = run_until_stopped(*e.fmu, c, 0.05, 100);
  EXPECT_NEAR(t, tr.stop_time, 1e-10);
  EXPECT_NEAR(t, kGroundTime, 1e-10);
  EXPECT_NEAR(e.fmu->get(c, "z"), 0.0, 1e-9);
  EXPECT_NEAR(e.fmu->get(c, "z_dot"), -9.81 * kGroundTime, 1e-8);
  e.fmu->free_instance(c);
  EXPECT_TRUE(log.messages.empty()) << log.messages.front();
}

// A condition on a constraint multiplier (the row's λ column, from the KKT solve): the Cartesian
// pendulum released at 1 rad, whose rod tension λ = m (v² − g y) / l² rises from 5.3 to 18.8 N on
// the way down, stops where simulate stops.
TEST(ExportFmu, StopWhenOnAMultiplierMatchesSimulate) {
  Exported& e = exported("cartesian_taut", [] {
    std::ifstream in(testing::example_path("cartesian_pendulum.yaml"));
    std::stringstream text;
    text << in.rdbuf() << "stop_when: {taut: rod > 12}\n";
    return testing::load_string(text.str());
  });
  const Trajectory tr = e.sys.run(e.sys.options());
  ASSERT_EQ(tr.stopped_by, "taut");
  FmuLog log;
  fmi2Component c = start_cs(*e.fmu, log);
  const double t = run_until_stopped(*e.fmu, c, 0.01, 100);
  EXPECT_NEAR(t, tr.stop_time, 1e-9);
  EXPECT_NEAR(e.fmu->get(c, "rod"), 12.0, 1e-7);
  e.fmu->free_instance(c);
}

// Model Exchange: the indicators are g = rhs − lhs (0 − height for `height < 0`), changing sign
// at the closed-form time; the event there asks the importer to terminate, one before it does not.
TEST(ExportFmu, EventIndicatorChangesSignAtTheClosedFormTime) {
  FmuImporter& f = *ball().fmu;
  FmuLog log;
  fmi2Component c = f.make(fmi2ModelExchange, log);
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(f.enter_init(c), fmi2OK);
  ASSERT_EQ(f.exit_init(c), fmi2OK);
  fmi2EventInfo info{};
  ASSERT_EQ(f.new_discrete_states(c, &info), fmi2OK);
  EXPECT_EQ(info.terminateSimulation, fmi2False);
  ASSERT_EQ(f.enter_continuous(c), fmi2OK);
  double z[2];
  EXPECT_EQ(f.get_event_indicators(c, z, 1), fmi2Error);  // the wrong count
  EXPECT_NE(log.messages.back().find("expected 2 event indicators"), std::string::npos);
  ASSERT_EQ(f.reset(c), fmi2OK);
  ASSERT_EQ(f.enter_init(c), fmi2OK);
  ASSERT_EQ(f.exit_init(c), fmi2OK);
  ASSERT_EQ(f.new_discrete_states(c, &info), fmi2OK);
  ASSERT_EQ(f.enter_continuous(c), fmi2OK);
  for (const double dt : {-1e-6, 1e-6}) {
    const double t = kGroundTime + dt;
    const double x[2] = {2.0 - 9.81 * t * t / 2, -9.81 * t};
    ASSERT_EQ(f.set_time(c, t), fmi2OK);
    ASSERT_EQ(f.set_states(c, x, 2), fmi2OK);
    ASSERT_EQ(f.get_event_indicators(c, z, 2), fmi2OK);
    EXPECT_DOUBLE_EQ(z[0], -100.0 - x[1]);  // fast: z_dot < −100
    EXPECT_NEAR(z[1], -x[0], 1e-15);        // ground: height < 0
    EXPECT_EQ(z[1] > 0, dt > 0) << "at t* + " << dt;
    ASSERT_EQ(f.enter_event_mode(c), fmi2OK);
    ASSERT_EQ(f.new_discrete_states(c, &info), fmi2OK);
    EXPECT_EQ(info.terminateSimulation, dt > 0 ? fmi2True : fmi2False) << "at t* + " << dt;
    ASSERT_EQ(f.enter_continuous(c), fmi2OK);
  }
  f.free_instance(c);
}

// The description an importer reads: states with their derivatives, the model's parameters with
// values, outputs listed in the model structure.
TEST(ExportFmu, DescriptionListsStatesParametersAndOutputs) {
  Exported& e = cartesian();
  const FmuImporter& f = *e.fmu;
  EXPECT_EQ(f.identifier, "cartesian_pendulum");
  EXPECT_EQ(f.structure.at("Derivatives").size(), 4u);
  EXPECT_EQ(f.order[f.structure.at("Derivatives")[0] - 1], "der(x)");
  EXPECT_EQ(f.variables.at("g").causality, "parameter");
  EXPECT_EQ(f.variables.at("g").start, 9.81);
  EXPECT_EQ(f.variables.at("x").start, e.sys.compiled->q0[0]);
  std::set<std::string> outputs;
  for (unsigned i : f.structure.at("Outputs")) outputs.insert(f.order[i - 1]);
  EXPECT_EQ(outputs, (std::set<std::string>{"x", "y", "x_dot", "y_dot", "rod", "kinetic",
                                            "potential", "energy"}));
}

// The binary needs only libc and libm (and the loader) at run time.
TEST(ExportFmu, BinaryIsSelfContained) {
  const std::string cmd = "readelf -d '" + pendulum().fmu->library + "'";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::set<std::string> needed;
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) {
    const std::string s(line);
    if (s.find("(NEEDED)") == std::string::npos) continue;
    needed.insert(s.substr(s.find('[') + 1, s.find(']') - s.find('[') - 1));
  }
  ASSERT_EQ(pclose(pipe), 0);
  EXPECT_FALSE(needed.empty());
  for (const std::string& lib : needed)
    EXPECT_TRUE(lib == "libc.so.6" || lib == "libm.so.6" || lib.rfind("ld-linux", 0) == 0) << lib;
}

TEST(ExportFmu, BadFmiTypeIsRefused) {
  const testing::Loaded sys = testing::load_example("pendulum.yaml");
  FmuOptions o = fmu_options(*sys.model);
  o.fmi_type = "cosim";
  const fs::path out =
      fs::temp_directory_path() / ("lagrange_fmu_bad_type_" + std::to_string(::getpid()) + ".fmu");
  fs::remove(out);
  EXPECT_THROW(export_fmu(*sys.compiled, o, out.string()), std::invalid_argument);
  EXPECT_FALSE(fs::exists(out));
}

// The Panda with joint torques as FMI inputs (docs/fmu.md, "Examples"), driven from here as a
// controller would drive it. `lagrange eval --format json` gives M(q) and the bias forces, which
// at rest are the gravity torques g(q).
struct PandaEval {
  std::vector<std::vector<double>> M;
  std::vector<double> gravity;
};

const char* const kTau[] = {"tau1", "tau2", "tau3", "tau4", "tau5", "tau6", "tau7"};
const char* const kJoint[] = {"panda_joint1", "panda_joint2", "panda_joint3", "panda_joint4",
                              "panda_joint5", "panda_joint6", "panda_joint7"};

PandaEval panda_eval(const std::vector<double>& q) {
  std::string state;
  for (size_t i = 0; i < q.size(); ++i) {
    char value[64];
    std::snprintf(value, sizeof value, "%.17g", q[i]);
    state += (i ? "," : "") + std::string(kJoint[i]) + "=" + value;
  }
  const hardening::ScratchDir dir("panda_eval");
  const hardening::RunResult r =
      hardening::run_lagrange(dir.path(), {"eval", testing::example_path("fmu/panda_torques.yaml"),
                                           "--state", state, "--format", "json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("v"), std::vector<double>(7, 0.0));
  return {j.at("M").get<std::vector<std::vector<double>>>(),
          j.at("bias").get<std::vector<double>>()};
}

/// The largest |q − q_ref| and |q̇| over the Panda's joints in instance c.
struct JointGap {
  double position = 0.0, speed = 0.0;
};
JointGap joint_gap(FmuImporter& f, fmi2Component c, const std::vector<double>& q_ref) {
  JointGap g;
  for (size_t i = 0; i < 7; ++i) {
    g.position = std::max(g.position, std::abs(f.get(c, kJoint[i]) - q_ref[i]));
    g.speed = std::max(g.speed, std::abs(f.get(c, std::string(kJoint[i]) + "_dot")));
  }
  return g;
}

// Holding torques equal to the gravity torques that `lagrange eval` gives at the ready pose keep
// the arm there: after 1 s every joint within 1e-6 rad of where it started and at rest to 1e-6
// rad/s. Zero torques (the inputs' declared value) let it fall: the inputs are what holds it.
TEST(ExportFmu, PandaHeldByGravityTorquesSetAsInputs) {
  Exported& e = panda();
  FmuImporter& f = *e.fmu;
  for (const char* tau : kTau) EXPECT_EQ(f.variables.at(tau).causality, "input") << tau;
  const std::vector<double> q0(e.sys.compiled->q0.begin(), e.sys.compiled->q0.end());
  const PandaEval at_rest = panda_eval(q0);
  ASSERT_GT(std::abs(at_rest.gravity[3]), 20.0);  // the elbow carries the forearm and hand

  FmuLog log;
  fmi2Component held = start_cs(f, log), falling = start_cs(f, log);
  for (size_t i = 0; i < 7; ++i) ASSERT_EQ(f.set(held, kTau[i], at_rest.gravity[i]), fmi2OK);
  for (int k = 0; k < 100; ++k) {
    ASSERT_EQ(f.do_step(held, 0.01 * k, 0.01, fmi2True), fmi2OK);
    ASSERT_EQ(f.do_step(falling, 0.01 * k, 0.01, fmi2True), fmi2OK);
  }
  const auto [drift, speed] = joint_gap(f, held, q0);
  const double fall = joint_gap(f, falling, q0).position;
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(speed, 1e-6);
  EXPECT_GT(fall, 0.5);
  std::printf(
      "Panda held by eval's gravity torques for 1 s: max |q - q0| %.2e rad, "
      "max |v| %.2e rad/s; with zero torques max |q - q0| %.2f rad\n",
      drift, speed, fall);
  f.free_instance(held);
  f.free_instance(falling);
  EXPECT_TRUE(log.messages.empty()) << log.messages.front();
}

// A PD controller with gravity compensation at the target, sampled every 0.01 s and held, moves
// the Panda from its ready pose to another pose, up to 0.5 rad away per joint:
// τ = g(q_d) + M(q_d) (ω² (q_d − q) − 2ω q̇), with g(q_d) and M(q_d) from `lagrange eval` at q_d
// (ω = 20 rad/s: critically damped near q_d, 2ωh = 0.4 per sample). The gains ω² M(q_d) and
// 2ω M(q_d) are constant and positive definite, and the stiffness dominates the gravity torques'
// gradient, so q_d is the equilibrium the arm settles at: after 3 s within 1e-6 rad, at rest.
TEST(ExportFmu, PandaPdControllerReachesTargetThroughTorqueInputs) {
  Exported& e = panda();
  FmuImporter& f = *e.fmu;
  const std::vector<double> q0(e.sys.compiled->q0.begin(), e.sys.compiled->q0.end());
  const double offset[] = {0.3, 0.25, -0.3, 0.4, 0.3, -0.3, 0.5};
  std::vector<double> target(7);
  for (size_t i = 0; i < 7; ++i) target[i] = q0[i] + offset[i];
  const PandaEval at_target = panda_eval(target);
  const double omega = 20.0;
  FmuLog log;
  fmi2Component c = start_cs(f, log);
  const double h = 0.01;
  double first_error = 0.0;
  for (int k = 0; k < 300; ++k) {
    double command[7];  // ω² (q_d − q) − 2ω q̇
    for (size_t i = 0; i < 7; ++i) {
      const double q = f.get(c, kJoint[i]), v = f.get(c, std::string(kJoint[i]) + "_dot");
      command[i] = omega * omega * (target[i] - q) - 2.0 * omega * v;
      if (k == 0) first_error = std::max(first_error, std::abs(target[i] - q));
    }
    for (size_t i = 0; i < 7; ++i) {
      double tau = at_target.gravity[i];
      for (size_t j = 0; j < 7; ++j) tau += at_target.M[i][j] * command[j];
      ASSERT_EQ(f.set(c, kTau[i], tau), fmi2OK);
    }
    ASSERT_EQ(f.do_step(c, h * k, h, fmi2True), fmi2OK) << "step " << k;
  }
  const auto [error, speed] = joint_gap(f, c, target);
  EXPECT_NEAR(first_error, 0.5, 1e-12);
  EXPECT_LT(error, 1e-6);
  EXPECT_LT(speed, 1e-5);
  std::printf(
      "Panda PD + gravity at the target, 0.01 s samples: max |q - q_d| from %.2f to %.2e "
      "rad in 3 s, max |v| %.2e rad/s\n",
      first_error, error, speed);
  f.free_instance(c);
  EXPECT_TRUE(log.messages.empty()) << log.messages.front();
}

}  // namespace
}  // namespace lagrange
