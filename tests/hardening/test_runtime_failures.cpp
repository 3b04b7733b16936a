// Failures at run time, interruption and determinism through the command line (issue 5).
// A failed run exits 3 with the time, the cause and the offending values, and keeps the rows
// computed so far under the final name with a sidecar saying "failed"; Ctrl-C keeps them with
// "interrupted"; no run leaves a ".part" file; the same run twice writes the same bytes.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/test_paths.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::example_path;

/// The CSV parsed into rows of numbers; fails the test on a malformed line.
std::vector<std::vector<double>> parse_csv(const std::string& text, size_t* columns) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  *columns = static_cast<size_t>(std::count(line.begin(), line.end(), ',')) + 1;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      size_t used = 0;
      row.push_back(std::stod(cell, &used));
      EXPECT_EQ(used, cell.size()) << "bad cell '" << cell << "'";
    }
    EXPECT_EQ(row.size(), *columns) << "short row: " << line;
    rows.push_back(row);
  }
  EXPECT_TRUE(text.empty() || text.back() == '\n') << "the CSV does not end with a newline";
  return rows;
}

/// A run that must fail: its stderr, sidecar and rows, checked for what every failure must have.
struct Failure {
  RunResult result;
  nlohmann::json sidecar;
  std::vector<std::vector<double>> rows;
};

Failure run_failing(const ScratchDir& dir, const std::string& yaml,
                    std::vector<std::string> extra) {
  const fs::path model = dir.path() / "model.yaml", csv = dir.path() / "out.csv";
  spit(model, yaml);
  std::vector<std::string> args{"simulate", model.string(), "-o", csv.string(), "-q"};
  args.insert(args.end(), extra.begin(), extra.end());
  Failure f;
  f.result = run_lagrange(dir.path(), args);
  EXPECT_EQ(f.result.exit_code, 3) << f.result.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"model.yaml", "out.csv", "out.csv.json"}));
  f.sidecar = nlohmann::json::parse(slurp(dir.path() / "out.csv.json"));
  EXPECT_EQ(f.sidecar.at("status"), "failed");
  EXPECT_TRUE(f.sidecar.contains("reason"));
  size_t columns = 0;
  f.rows = parse_csv(slurp(csv), &columns);
  EXPECT_EQ(f.sidecar.at("rows").get<size_t>(), f.rows.size());
  // "simulation failed at t = <time>: <cause>", and the same reason in the sidecar
  std::smatch m;
  EXPECT_TRUE(
      std::regex_search(f.result.err, m, std::regex("simulation failed at t = ([-0-9.e+]+): ")))
      << f.result.err;
  if (!m.empty()) {
    EXPECT_DOUBLE_EQ(std::stod(m[1].str()), f.sidecar.at("failure_time").get<double>());
  }
  // The work done until a mid-run failure is kept (issue 25 item 10: it read 0 and 0).
  if (f.sidecar.at("failure_time").get<double>() > 0) {
    EXPECT_GT(f.sidecar.at("steps").get<long>(), 0) << f.sidecar.dump();
    EXPECT_GT(f.sidecar.at("rhs_evaluations").get<long>(), f.sidecar.at("steps").get<long>())
        << f.sidecar.dump();
  }
  return f;
}

const std::string kSqrtThroughZero =
    "name: sqrt through zero\n"
    "coordinates:\n  x: {initial: 1, rate: -10}\n"
    "kinetic: der(x)^2/2\n"
    "potential: x^(5/2)\n"
    "simulate: {t_end: 1, output_step: 0.01}\n";

TEST(RuntimeFailure, NanInTheStateKeepsRowsBeforeIt) {
  ScratchDir dir("nan");
  const Failure f = run_failing(dir, kSqrtThroughZero, {});
  // x = 1 − 10 t crosses zero near t = 0.1, where x^(5/2) has no real value
  const double t = f.sidecar.at("failure_time").get<double>();
  EXPECT_GT(t, 0.05);
  EXPECT_LT(t, 0.2);
  ASSERT_FALSE(f.rows.empty());
  EXPECT_LE(f.rows.back()[0], t);
  EXPECT_NE(f.result.err.find("not finite"), std::string::npos) << f.result.err;
  // the cause: the potential's force, not the solve
  EXPECT_NE(f.result.err.find("the generalised forces on 'x' are not finite (an expression of the "
                              "model has no finite value here)"),
            std::string::npos)
      << f.result.err;
  EXPECT_NE(f.result.err.find("x = -"), std::string::npos) << f.result.err;  // the state
}

TEST(RuntimeFailure, NanInTheStateWithFixedStepRk4) {
  ScratchDir dir("nan-rk4");
  const Failure f = run_failing(dir, kSqrtThroughZero, {"--integrator", "rk4"});
  EXPECT_NE(f.result.err.find("the generalised forces on 'x' are not finite"), std::string::npos)
      << f.result.err;
}

TEST(RuntimeFailure, EveryIntegratorKeepsItsStatisticsOnFailure) {
  for (const char* method : {"dop853", "arkode", "cvode", "rk4", "midpoint", "ida"}) {
    SCOPED_TRACE(method);
    ScratchDir dir(std::string("stats-") + method);
    (void)run_failing(dir, kSqrtThroughZero, {"--integrator", method});
  }
}

TEST(RuntimeFailure, InfiniteAccelerationOnACollapse) {
  // Radial fall onto a 1/r well: r reaches 0 in finite time (t = π/(2√2) ≈ 1.11) where the
  // acceleration −1/r² grows without bound: the default method's step size collapses there (or,
  // for a method that steps on, the acceleration stops being finite).
  ScratchDir dir("collapse");
  const Failure f =
      run_failing(dir,
                  "name: collapse\ncoordinates:\n  r: {initial: 1}\n"
                  "kinetic: der(r)^2/2\npotential: -1/r\n"
                  "simulate: {t_end: 3, output_step: 0.01, rtol: 1e-10, atol: 1e-12}\n",
                  {});
  const double t = f.sidecar.at("failure_time").get<double>();
  EXPECT_NEAR(t, 3.14159265358979 / (2 * std::sqrt(2.0)), 1e-3);
  EXPECT_GT(f.rows.size(), 100u);
  const std::string& err = f.result.err;
  EXPECT_TRUE(err.find("the acceleration of 'r' is not finite") != std::string::npos ||
              err.find("dop853: the step size fell") != std::string::npos)
      << err;
  EXPECT_NE(err.find("r_ddot = -"), std::string::npos) << err;  // the state, where it went
}

TEST(CompleteButWrong, EveryIntegratorStopsAtTheCollapse) {
  // The radial fall onto −1/r again at the default tolerances, under every method. cvode, ida and
  // rk4 once stepped across r = 0 and exited 0 with T + U gone from −1 to 2.4e34, 6.4e26 and
  // 657 (issue 25 item 5). The energy of this conservative model is a constant of motion, so
  // every method now fails within one output step of the collapse at π/(2√2).
  const double collapse = 3.14159265358979 / (2 * std::sqrt(2.0));
  for (const char* method :
       {"dop853", "arkode", "cvode", "cvode:jacobian", "ida", "ida:jacobian", "rk4", "midpoint"}) {
    SCOPED_TRACE(method);
    ScratchDir dir(std::string("collapse-") + method);
    const Failure f = run_failing(dir,
                                  "name: collapse\ncoordinates:\n  r: {initial: 1}\n"
                                  "kinetic: der(r)^2/2\npotential: -1/r\n"
                                  "simulate: {t_end: 3, output_step: 0.01}\n",
                                  {"--integrator", method});
    const double t = f.sidecar.at("failure_time").get<double>();
    EXPECT_GT(t, collapse - 0.01);
    EXPECT_LE(t, collapse + 0.01);
    // the kept rows conserve the energy −1 of the start, up to the last ones next to the
    // singularity, where the methods' own error grows (rk4's to 3e-3 at t = 1.10)
    const size_t energy = 5;  // t, r, r_dot, kinetic, potential, energy
    for (const auto& row : f.rows) {
      if (row[0] < 1.095) {
        EXPECT_NEAR(row[energy], -1.0, 1e-3) << "t = " << row[0];
      }
    }
  }
}

TEST(CompleteButWrong, TheEnergyCheckNamesTheJumpAndTheSamples) {
  ScratchDir dir("collapse-energy");
  const Failure f = run_failing(dir,
                                "name: collapse\ncoordinates:\n  r: {initial: 1}\n"
                                "kinetic: der(r)^2/2\npotential: -1/r\n"
                                "simulate: {t_end: 3, output_step: 0.01}\n",
                                {"--integrator", "rk4"});
  const std::string& err = f.result.err;
  EXPECT_NE(err.find("the energy T + U of this conservative model"), std::string::npos) << err;
  EXPECT_NE(err.find("went from -1 at t = 0 to "), std::string::npos) << err;
  EXPECT_NE(err.find("stepped across a singularity"), std::string::npos) << err;
  // the row past the jump is not kept
  EXPECT_LT(f.rows.back()[0], f.sidecar.at("failure_time").get<double>());
}

TEST(CompleteButWrong, EnergyThatIsNotAConstantOfMotionIsNotChecked) {
  // L = ẋ²/2 + x ẋ − x²/2: the x ẋ term is d(x²/2)/dt, so the motion is the unit oscillator, but
  // the conserved energy is ẋ²/2 + x²/2, not T + U (which swings by x ẋ, as much as T itself).
  // The run is complete, and right: x = cos t.
  ScratchDir dir("gauge");
  const fs::path model = dir.path() / "m.yaml", csv = dir.path() / "out.csv";
  spit(model,
       "coordinates:\n  x: {initial: 1}\nkinetic: der(x)^2/2 + x*der(x)\npotential: x^2/2\n"
       "simulate: {t_end: 6, output_step: 0.1, rtol: 1e-10, atol: 1e-12}\n");
  const RunResult r = run_lagrange(
      dir.path(), {"simulate", model.string(), "-o", csv.string(), "-q", "--integrator", "rk4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  size_t columns = 0;
  const auto rows = parse_csv(slurp(csv), &columns);
  ASSERT_EQ(rows.size(), 61u);
  for (const auto& row : rows) EXPECT_NEAR(row[1], std::cos(row[0]), 1e-6) << "t = " << row[0];
}

TEST(CompleteButWrong, AnEnergyWithoutAValueFailsTheRun) {
  // The motion is a free particle (T's last term has no q or v in it), but T has no value
  // past t = 0.5: the rows once carried -nan in kinetic and energy with exit 0.
  ScratchDir dir("nan-energy");
  const Failure f = run_failing(dir,
                                "name: undefined energy\ncoordinates:\n  x: {initial: 0, rate: 1}\n"
                                "kinetic: der(x)^2/2 + sqrt(1/2 - t)\n"
                                "simulate: {t_end: 1, output_step: 0.01}\n",
                                {});
  const double t = f.sidecar.at("failure_time").get<double>();
  EXPECT_NEAR(t, 0.51, 1e-9);  // the first sample past 1/2
  EXPECT_EQ(f.rows.size(), 51u);
  EXPECT_NE(f.result.err.find("the energy 'kinetic' is not finite"), std::string::npos)
      << f.result.err;
  for (const auto& row : f.rows) EXPECT_NEAR(row[1], row[0], 1e-12);  // x = t until then
}

const std::string kWinch =
    "name: winch\nparameters: {R: 0.2, J: 0.05, mu: 0.4, L: 30, g: 9.81}\n"
    "gravity: [0, 0, -g]\n"
    "winches:\n  drum:\n    tether: line\n    radius: R\n    inertia: J\n"
    "    total_length: L\n";
const std::string kWinchLine =
    "tethers:\n  line:\n    between: [[0, 0, 0], free]\n    segments: 2\n"
    "    mass_per_length: mu\n";

TEST(CompleteButWrong, AWinchReelingInThroughZeroFailsWhereItHappens) {
  // A prescribed reeled-out length 1 − t reaches 0 at exactly t = 1; the run once went on to
  // −0.67 m with exit 0. Located between samples like a stop condition.
  ScratchDir dir("winch-prescribed");
  const Failure f = run_failing(
      dir,
      kWinch + "    reeled_out: 1 - t\n" + kWinchLine + "simulate: {t_end: 2, output_step: 0.03}\n",
      {});
  EXPECT_NEAR(f.sidecar.at("failure_time").get<double>(), 1.0, 1e-9);
  EXPECT_NE(f.result.err.find("winch 'drum' reeled its tether in completely"), std::string::npos)
      << f.result.err;
  EXPECT_NE(f.result.err.find("drum.reeled_out < 0 became true ("), std::string::npos)
      << f.result.err;
  EXPECT_NE(f.result.err.find("model.yaml:5:3)"), std::string::npos) << f.result.err;
  for (const auto& row : f.rows) EXPECT_GT(row[1], 0.0);
}

TEST(CompleteButWrong, AWinchPulledInByItsMotorFailsWhereItHappens) {
  // The case: a motor torque reels the hanging tether in through zero.
  ScratchDir dir("winch-torque");
  const Failure f = run_failing(dir,
                                kWinch + "    torque: -20\n    initial: {reeled_out: 1}\n" +
                                    kWinchLine + "simulate: {t_end: 2, output_step: 0.01}\n",
                                {});
  const double t = f.sidecar.at("failure_time").get<double>();
  ASSERT_GE(f.rows.size(), 2u);
  const auto& last = f.rows.back();
  EXPECT_GT(last[1], 0.0);  // the last kept row still has tether out
  EXPECT_GT(t, last[0]);    // and the crossing lies after it, within one step
  EXPECT_LT(t, last[0] + 0.01);
  // ℓ(t) is smooth: the crossing is where the last row's ℓ + ℓ̇ (t − t_row) ≈ 0 to O(dt²)
  const size_t speed_column = 8;  // t, ℓ, node1 xyz, node2 xyz, ℓ̇
  EXPECT_NEAR(t, last[0] - last[1] / last[speed_column], 2e-3);
}

TEST(RuntimeFailure, IntegratorGivesUpOnAStiffSpring) {
  // ω = 10¹⁰ rad/s: the explicit method's stable step is far below what max_steps can cover
  // before the first output sample, so ARKODE gives up with too much work.
  ScratchDir dir("stiff");
  const Failure f =
      run_failing(dir,
                  "name: stiff\nparameters: {k: 1e20}\ncoordinates:\n  x: {initial: 1}\n"
                  "kinetic: der(x)^2/2\npotential: k*x^2/2\n"
                  "simulate: {t_end: 1, output_step: 0.01}\n",
                  {});
  EXPECT_LT(f.sidecar.at("failure_time").get<double>(), 0.01);
  EXPECT_EQ(f.rows.size(), 1u);  // the initial sample
  EXPECT_NE(f.result.err.find("TOO_MUCH_WORK"), std::string::npos) << f.result.err;
  // where it gave up, and the largest quantities there (the acceleration −k x)
  EXPECT_NE(f.result.err.find("last evaluated state at t = "), std::string::npos) << f.result.err;
  EXPECT_NE(f.result.err.find("largest values: x_ddot = "), std::string::npos) << f.result.err;
}

TEST(RuntimeFailure, MassMatrixBecomesSingularMidRun) {
  // M = 1 − t loses definiteness at t = 1: rk4 on a 10 ms grid steps onto it.
  ScratchDir dir("singular");
  const Failure f =
      run_failing(dir,
                  "name: fading mass\ncoordinates:\n  x: {initial: 0, rate: 1}\n"
                  "kinetic: (1 - t)*der(x)^2/2\n"
                  "simulate: {t_end: 2, output_step: 0.01, integrator: rk4, step: 0.001}\n",
                  {});
  const double t = f.sidecar.at("failure_time").get<double>();
  EXPECT_NEAR(t, 1.0, 1e-2);
  EXPECT_GT(f.rows.size(), 90u);
  EXPECT_NE(f.result.err.find("mass matrix is singular"), std::string::npos) << f.result.err;
  EXPECT_NE(f.result.err.find("x_dot = "), std::string::npos) << f.result.err;
}

TEST(RuntimeFailure, MidpointNamesAStepThatConvergesOnATautTether) {
  // The elastic tether's damped segments (D/l₀ = 180 N·s/m on 77 g nodes) make the taut line's
  // rates some 2000/s: at h = 1 ms a fixed-point sweep scales the change by more than 1. The
  // message names the step that makes the sweeps contract, and that step runs.
  ScratchDir dir("midpoint-step");
  const auto run = [&](const std::string& step) {
    return run_lagrange(
        dir.path(), {"simulate", example_path("elastic_tether.yaml"), "--integrator", "midpoint",
                     "--step", step, "--t-end", "0.3", "-q"});
  };
  const RunResult failed = run("1e-3");
  ASSERT_EQ(failed.exit_code, 3) << failed.err;
  const std::string marker = "lower --step to about ";
  const size_t at = failed.err.find(marker);
  ASSERT_NE(at, std::string::npos) << failed.err;
  EXPECT_NE(failed.err.find("--integrator cvode or ida"), std::string::npos) << failed.err;
  const std::string suggested = failed.err.substr(at + marker.size()).substr(0, 6);
  const double h = std::stod(suggested);
  EXPECT_LT(h, 2e-4) << failed.err;
  EXPECT_GT(h, 1e-5) << failed.err;
  const RunResult ok = run(std::to_string(h));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(RuntimeFailure, SuccessWritesACompleteSidecarWithStatistics) {
  ScratchDir dir("complete");
  const fs::path csv = dir.path() / "out.csv";
  const RunResult r = run_lagrange(dir.path(), {"simulate", example_path("pendulum.yaml"), "-o",
                                                csv.string(), "--t-end", "1", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"out.csv", "out.csv.json"}));
  const auto side = nlohmann::json::parse(slurp(dir.path() / "out.csv.json"));
  EXPECT_EQ(side.at("status"), "complete");
  EXPECT_EQ(side.at("rows").get<size_t>(), 101u);
  EXPECT_GT(side.at("steps").get<long>(), 0);
  EXPECT_GT(side.at("rhs_evaluations").get<long>(), 0);
}

TEST(Interruption, SigintKeepsACompleteCsvMarkedInterrupted) {
  ScratchDir dir("sigint");
  const fs::path csv = dir.path() / "out.csv";
  Child child(dir.path(), {"simulate", example_path("double_pendulum.yaml"), "-o", csv.string(),
                           "--t-end", "1e5", "-q"});
  std::this_thread::sleep_for(std::chrono::seconds(1));
  child.signal(SIGINT);
  const RunResult r = child.wait(std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted at t = "), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"out.csv", "out.csv.json"}));
  const auto side = nlohmann::json::parse(slurp(dir.path() / "out.csv.json"));
  EXPECT_EQ(side.at("status"), "interrupted");
  size_t columns = 0;
  const auto rows = parse_csv(slurp(csv), &columns);
  ASSERT_GT(rows.size(), 1u);
  EXPECT_EQ(side.at("rows").get<size_t>(), rows.size());
  EXPECT_DOUBLE_EQ(side.at("t_last").get<double>(), rows.back()[0]);
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_NEAR(rows[i][0] - rows[i - 1][0], 0.01, 1e-9);
  EXPECT_LT(rows.back()[0], 1e7);
}

TEST(Interruption, SigintBeforeAnyFileLeavesNoPartFile) {
  // Interrupted while deriving: the run still ends with 130 or a kept trajectory, never a ".part".
  ScratchDir dir("sigint-early");
  const fs::path csv = dir.path() / "out.csv";
  Child child(dir.path(),
              {"simulate", example_path("n_link_pendulum_5.yaml"), "-o", csv.string(), "-q"});
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  child.signal(SIGINT);
  const RunResult r = child.wait(std::chrono::seconds(120));
  EXPECT_TRUE(r.exit_code == 130 || r.exit_code == 0) << r.exit_code << " " << r.err;
  for (const auto& name : dir.files()) EXPECT_EQ(name.find(".part"), std::string::npos) << name;
}

/// Simulates `model` with `extra` options twice and compares the CSV bytes.
void expect_bit_identical(const std::string& label, const std::string& model,
                          std::vector<std::string> extra) {
  ScratchDir dir("determinism-" + label);
  std::string first;
  for (int run = 0; run < 2; ++run) {
    const fs::path csv = dir.path() / ("run" + std::to_string(run) + ".csv");
    std::vector<std::string> args{"simulate", model, "-o", csv.string(), "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_lagrange(dir.path(), args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string bytes = slurp(csv);
    ASSERT_GT(bytes.size(), 1000u);
    if (run == 0)
      first = bytes;
    else
      EXPECT_TRUE(bytes == first) << label << ": the two CSV files differ";
  }
}

TEST(Determinism, SameModelAndOptionsGiveTheSameBytes) {
  expect_bit_identical("arkode", example_path("double_pendulum.yaml"), {"--t-end", "5"});
  expect_bit_identical("cvode", example_path("five_bar.yaml"),
                       {"--t-end", "2", "--integrator", "cvode"});
  expect_bit_identical("ida", example_path("constrained_pendulum.yaml"),
                       {"--t-end", "2", "--integrator", "ida"});
  expect_bit_identical("rk4", example_path("crane.yaml"),
                       {"--t-end", "2", "--integrator", "rk4", "--set", "g=9.7"});
}

}  // namespace
}  // namespace lagrange::hardening
