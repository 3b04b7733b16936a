// An initial state that cannot be made consistent (issue 8, item 2) is a mistake in the model:
// `check` and `simulate` exit 1 before any file is written, naming the constraints not met, by
// how much, and the `fixed: true` coordinates in the way. A state that can be projected is.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// A Cartesian pendulum bob at (x, y) on a rod of length l = 1; `coordinates` and `rod` vary.
std::string pendulum(const std::string& coordinates, const std::string& rod) {
  return "parameters: {m: 1, g: 9.81, l: 1}\ncoordinates:\n" + coordinates +
         "points: {bob: [x, y, 0]}\nparticles: {bob: m}\ngravity: [0, -g, 0]\n"
         "constraints: {rod: " +
         rod + "}\n";
}

const std::string kRod = "(x^2 + y^2 - l^2)/2";

// Runs `check` and `simulate -o out.csv --plot out.svg` on `yaml`: both must exit 1 with
// `fragments` in the message, located at `where`, and leave nothing but the model file.
void expect_model_error(const std::string& label, const std::string& yaml, const std::string& where,
                        const std::vector<std::string>& fragments) {
  ScratchDir dir("initial-" + label);
  const fs::path model = dir.path() / "start.yaml";
  spit(model, yaml);
  const fs::path csv = dir.path() / "out.csv", svg = dir.path() / "out.svg";
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"check", model.string()},
           {"simulate", model.string(), "-o", csv.string(), "--plot", svg.string()}}) {
    const RunResult r = run_lagrange(dir.path(), args);
    EXPECT_EQ(r.exit_code, 1) << args[0] << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(model.string() + ":" + where +
                         ": error: the initial state cannot be "
                         "made consistent"),
              std::string::npos)
        << args[0] << "\n"
        << r.err;
    for (const auto& f : fragments)
      EXPECT_NE(r.err.find(f), std::string::npos) << f << "\n" << r.err;
    EXPECT_EQ(r.out.find("model ok"), std::string::npos) << r.out;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"start.yaml"}) << args[0];
  }
}

TEST(InitialState, FixedCoordinatesThatMakeTheRodImpossible) {
  expect_model_error("fixed",
                     pendulum("  x: {initial: 0.9, fixed: true}\n  y: {initial: -0.6, fixed: "
                              "true}\n",
                              kRod),
                     "8:15",
                     {"constraint 'rod': C = 0.085 (0.085 at the start)",
                      "the coordinates marked 'fixed: true' stand in the way: x = 0.9, y = -0.6"});
}

TEST(InitialState, OneFixedCoordinateOutOfReach) {
  // x = 2 on a rod of length 1: y cannot help.
  expect_model_error("fixed-x",
                     pendulum("  x: {initial: 2, fixed: true}\n  y: {initial: -0.6}\n", kRod),
                     "8:15", {"'rod': C = 1.5 (1.68 at the start)", "in the way: x = 2 ("});
}

TEST(InitialState, UnsatisfiableConstraint) {
  // x² + y² + l² > 0 everywhere: the projection stops at its least value, 1 at x = y = 0.
  expect_model_error("unsatisfiable",
                     pendulum("  x: {initial: 2}\n  y: {initial: 1}\n", "x^2 + y^2 + l^2"), "8:15",
                     {"'rod': C = 1 (6 at the start)", "a minimum of |C| that is not 0"});
}

TEST(InitialState, FixedVelocityBreaksTheRate) {
  // On the rod, but moving along x (fixed with its rate) makes Ċ = x ẋ = 0.8.
  expect_model_error(
      "rate",
      pendulum("  x: {initial: 0.8, rate: 1, fixed: true}\n  y: {initial: -0.6, fixed: true}\n",
               kRod),
      "8:15", {"'rod': Ċ = 0.8 (0.8 at the start)", "stand in the way: x = 0.8, y = -0.6"});
}

TEST(InitialState, AProjectableStateIsProjectedAndSimulated) {
  ScratchDir dir("initial-projectable");
  const fs::path model = dir.path() / "start.yaml", csv = dir.path() / "out.csv";
  spit(model, pendulum("  x: {initial: 0.9}\n  y: {initial: -0.6}\n", kRod));
  const RunResult check = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(check.exit_code, 1) << check.out << check.err;  // the file's state is inconsistent
  EXPECT_NE(check.out.find("initial state was inconsistent"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("x: 0.9 -> "), std::string::npos) << check.out;
  const RunResult sim =
      run_lagrange(dir.path(), {"simulate", model.string(), "--t-end", "0.1", "-o", csv.string()});
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_NE(sim.err.find("note: initial state was inconsistent"), std::string::npos) << sim.err;
  EXPECT_NE(slurp(csv.string() + ".json").find("\"complete\""), std::string::npos);
}

// A damper whose points coincide at the start has no direction to act along (its rate is 0/0):
// named at the damper (line 6), not as "the acceleration of 'x' is not finite"; apart, it runs.
TEST(InitialState, ADamperAtZeroLengthIsNamed) {
  ScratchDir dir("initial-damper");
  const fs::path model = dir.path() / "start.yaml";
  const auto write = [&](const std::string& x0) {
    spit(model, "parameters: {m: 1, c: 0.5}\ncoordinates: {x: {initial: " + x0 +
                    "}, y: {initial: 0}}\npoints: {anchor: [0, 0, 0], bob: [x, y, 0]}\n"
                    "particles: {bob: m}\ndampers:\n  - {between: [anchor, bob], c: c}\n");
  };
  write("0");
  const RunResult r = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find(model.string() + ":6:5: error: the damper between 'anchor' and 'bob' has "
                                        "length 0 at the initial state"),
            std::string::npos)
      << r.err;
  write("0.5");
  EXPECT_EQ(run_lagrange(dir.path(), {"check", model.string()}).exit_code, 0);
}

}  // namespace
}  // namespace lagrange::hardening
