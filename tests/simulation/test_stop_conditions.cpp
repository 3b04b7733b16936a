// stop_when (docs/model-language.md, "Stop conditions"): the run ends when a condition becomes
// true, at the time located to the integrator's tolerance, checked against the pendulum's exact
// quarter period, against a second formulation (a tension in Cartesian coordinates against an
// angle in polar ones), and through the CLI (summary line, sidecar).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "hardening/cli_runner.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::load_string;
using testing::Loaded;
using testing::tight;

constexpr double kPi = 3.14159265358979323846;

std::string pendulum(double theta0, const std::string& stop, const std::string& integrator) {
  return fmt::format(
      "name: pendulum\nparameters: {{m: 1.0, l: 1.0, g: 9.81}}\n"
      "coordinates: {{theta: {{initial: {:.17g}}}}}\n"
      "points: {{bob: [l*sin(theta), -l*cos(theta), 0]}}\nparticles: {{bob: m}}\n"
      "gravity: [0, -g, 0]\nstop_when: {{{}}}\n"
      "simulate: {{t_end: 10, output_step: 0.01, integrator: {}}}\n",
      theta0, stop, integrator);
}

// Released from θ₀ at rest, the pendulum reaches θ = 0 after a quarter period K(sin(θ₀/2))/ω₀.
TEST(StopConditions, PendulumStopsAtTheBottomAfterItsExactQuarterPeriod) {
  const double omega = std::sqrt(9.81), quarter = std::comp_ellint_1(std::sin(kPi / 4)) / omega;
  for (const std::string method : {"dop853", "arkode", "cvode", "rk4", "ida"}) {
    Loaded sys = load_string(pendulum(kPi / 2, "bottom: theta < 0", method));
    SimulationOptions so = sys.options();
    so.integrator.rtol = 1e-11;
    so.integrator.atol = 1e-13;
    const Trajectory tr = sys.run(so);
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << method << ": " << tr.message;
    EXPECT_EQ(tr.stopped_by, "bottom") << method;
    EXPECT_NEAR(tr.stop_time, quarter, 1e-9) << method;
    const size_t last = tr.rows() - 1;
    EXPECT_EQ(tr.at(last, "t"), tr.stop_time) << method;  // the run ends there
    EXPECT_LE(tr.at(last, "theta"), 0.0) << method;       // the condition holds at the last row
    EXPECT_NEAR(tr.at(last, "theta"), 0.0, 1e-9) << method;
    EXPECT_GT(tr.at(last - 1, "theta"), 0.0) << method;  // and not at the row before
  }
}

// A condition true at the start fires only when it next becomes true: θ > 0 from θ₀ = π/2 fires
// at three quarter periods, when the pendulum swings back through the bottom.
TEST(StopConditions, ConditionTrueAtTheStartFiresWhenItNextBecomesTrue) {
  const double omega = std::sqrt(9.81), quarter = std::comp_ellint_1(std::sin(kPi / 4)) / omega;
  Loaded sys = load_string(pendulum(kPi / 2, "back: theta > 0", "dop853"));
  const Trajectory tr = sys.run(tight(sys, 10, 0.01));
  EXPECT_EQ(tr.stopped_by, "back");
  EXPECT_NEAR(tr.stop_time, 3 * quarter, 1e-9);
}

// The rod tension of the Cartesian pendulum (a multiplier column) reaches m g (3 cos θ − 2 cos θ₀)
// exactly when the polar pendulum reaches θ: the two stop at the same time.
TEST(StopConditions, TensionInCartesianAndAngleInPolarCoordinatesStopTogether) {
  Loaded polar = load_string(pendulum(1.0, "half: theta < 0.5", "dop853"));
  const Trajectory p = polar.run(tight(polar, 10, 0.01));
  Loaded cartesian = load_string(
      "name: cartesian\nparameters: {m: 1.0, g: 9.81, l: 1.0}\n"
      "coordinates: {x: {initial: 0.8414709848078965}, y: {initial: -0.5403023058681398}}\n"
      "points: {bob: [x, y, 0]}\nparticles: {bob: m}\ngravity: [0, -g, 0]\n"
      "constraints: {rod: (x^2 + y^2 - l^2)/2}\n"
      "stop_when: {taut: abs(rod)*l > m*g*(3*cos(0.5) - 2*cos(1))}\n"
      "simulate: {t_end: 10, output_step: 0.01}\n");
  const Trajectory c = cartesian.run(tight(cartesian, 10, 0.01));
  ASSERT_EQ(p.stopped_by, "half");
  ASSERT_EQ(c.stopped_by, "taut");
  EXPECT_NEAR(c.stop_time, p.stop_time, 1e-8);
  EXPECT_GT(p.stop_time, 0.1);
}

TEST(StopConditions, UnknownNamesAndMissingComparisonsAreLocatedErrors) {
  try {
    // Names are checked against the columns once they are known: before the run starts.
    Loaded sys = load_string(pendulum(1.0, "bad: thet < 0", "dop853"));
    sys.run(sys.options());
    ADD_FAILURE() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().line, 7);
    EXPECT_NE(std::string(e.what()).find("thet"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stop condition 'bad'"), std::string::npos) << e.what();
  }
  try {
    load_string(pendulum(1.0, "bad: theta", "dop853"));
    ADD_FAILURE() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().line, 7);
    EXPECT_NE(std::string(e.what()).find("expected one comparison"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagrange

namespace lagrange::hardening {
namespace {

// The CLI says which condition fired and when, in the summary and in the sidecar; exit 0.
TEST(StopConditionsCli, SummaryAndSidecarSayWhichConditionFiredAndWhen) {
  ScratchDir dir("stop-" + std::to_string(getpid()));
  spit(dir.path() / "p.yaml",
       "name: p\nparameters: {m: 1, l: 1, g: 9.81}\n"
       "coordinates: {theta: {initial: 1.5707963267948966}}\n"
       "points: {bob: [l*sin(theta), -l*cos(theta), 0]}\n"
       "particles: {bob: m}\ngravity: [0, -g, 0]\n"
       "stop_when: {bottom: theta < 0}\n");
  const RunResult r = run_lagrange(dir.path(), {"simulate", (dir.path() / "p.yaml").string(), "-o",
                                                (dir.path() / "p.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("stopped at t = 0.59196"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stop_when 'bottom' (theta < 0) became true"), std::string::npos) << r.out;
  const auto side = nlohmann::json::parse(slurp(dir.path() / "p.csv.json"));
  EXPECT_EQ(side["status"], "complete");
  EXPECT_EQ(side["stopped_by"], "bottom");
  EXPECT_NEAR(side["stop_time"].get<double>(), 0.5919604869, 1e-8);
  EXPECT_EQ(side["t_last"].get<double>(), side["stop_time"].get<double>());
}

// An element's warning condition (a kite below the ground of its wind) does not end the run: it
// is printed once, under -q too, and kept in the sidecar.
TEST(StopConditionsCli, AKiteBelowTheGroundIsWarnedOnceEvenUnderQuiet) {
  ScratchDir dir("warn-" + std::to_string(getpid()));
  spit(dir.path() / "k.yaml",
       "name: k\ncoordinates: {x: {initial: 141.42}, y: {initial: 0}, z: {initial: 141.42}}\n"
       "points: {kite: [x, y, z]}\ngravity: [0, 0, -9.81]\nwind: {speed: 3}\n"
       "tethers: {main: {between: [[0, 0, 0], kite], segments: 1, length: 200, "
       "mass_per_length: 0.0046}}\n"
       "kites: {wing: {point: kite, preset: ap2, CL: 0.8, CD: 0.6}}\n"
       "simulate: {t_end: 15, output_step: 0.05}\n");
  const RunResult r = run_lagrange(dir.path(), {"simulate", (dir.path() / "k.yaml").string(), "-q",
                                                "-o", (dir.path() / "k.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string warning = "warning: from t = ";
  const size_t at = r.err.find(warning);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, at + 1), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("kite 'wing' flies below the ground of its wind profile (height 0)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("wing.height < 0, "), std::string::npos) << r.err;
  const auto side = nlohmann::json::parse(slurp(dir.path() / "k.csv.json"));
  EXPECT_EQ(side["status"], "complete");
  ASSERT_EQ(side["warnings"].size(), 1u);
  EXPECT_EQ(side["warnings"][0].get<std::string>().rfind("from t = ", 0), 0u);
}

}  // namespace
}  // namespace lagrange::hardening
