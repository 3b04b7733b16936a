// Bad kite input through the command line: exit code 1, a located message naming what is wrong,
// and no output file; and what `derive` shows of a kite's aerodynamic model.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// A point `kite` on a one-segment tether, a free body `plane`; the kite's own lines follow.
std::string model(const std::string& kite) {
  return "coordinates: {x: {initial: 60}, y: {initial: 0}, z: {initial: 80}}\n"
         "points: {kite: [x, y, z], spot: [0, 0, 60]}\n"
         "gravity: [0, 0, -9.81]\n"
         "wind: {speed: 10}\n"
         "bodies:\n  plane: {mass: 36.8, inertia: [25, 32, 56], frame: free,\n"
         "          initial: {position: [0, 0, 50]}}\n"
         "tethers:\n  main: {between: [[0, 0, 0], kite], segments: 1, length: 100,\n"
         "         mass_per_length: 0.0046}\n"
         "kites:\n  wing:\n" +
         kite;
}

/// Cases as (label, the lines under `kites: {wing: …}`, fragment), completed by model().
std::vector<BadModel> bad_kites() {
  std::vector<BadModel> cases = {
      {"unknown point", "    point: nowhere\n    preset: ap2\n    CL: 1\n",
       "expected a point name for point of kite wing, got 'nowhere'"},
      {"unknown body", "    body: glider\n    preset: ap2\n",
       "expected the name of a free body (frame: free) for kite 'wing', got 'glider' (free "
       "bodies: plane)"},
      {"negative area", "    point: kite\n    preset: ap2\n    area: -3\n    CL: 1\n",
       "expected a positive area of kite 'wing', got -3"},
      {"unknown preset", "    point: kite\n    preset: ap3\n    CL: 1\n",
       "expected a kite preset (ap2, megawes) for kite 'wing', got 'ap3'"},
      {"coefficient of an unknown name",
       "    body: plane\n    preset: ap2\n    coefficients: {Cm: -0.03 - 0.6*alhpa}\n", "alhpa"},
      {"point and body", "    point: kite\n    body: plane\n",
       "expected exactly one of 'point' (a point-mass kite) or 'body'"},
      {"no lift coefficient", "    point: kite\n    preset: ap2\n",
       "expected 'CL' (lift coefficient) in kite wing"},
      {"no area", "    point: kite\n    mass: 1\n    CL: 1\n    CD: 0.1\n",
       "expected 'area' in kite 'wing' (or a preset), got none"},
      {"point without a tether", "    point: spot\n    preset: ap2\n    CL: 1\n",
       "expected a tether ending at point 'spot' (its second end) for kite 'wing'"},
      {"misspelt key", "    point: kite\n    preset: ap2\n    CL: 1\n    rol: 0.1\n", "rol"},
      {"tension in a law",
       "    point: kite\n    preset: ap2\n    CL: 1\n    roll: 1e-4*main.tension_ground\n",
       "expected an expression of t and the state in roll of kite wing, got the constraint force "
       "'main.tension_ground'"},
  };
  for (BadModel& c : cases) c.yaml = model(c.yaml);
  return cases;
}

class BadKiteModel : public ::testing::TestWithParam<BadModel> {};

TEST_P(BadKiteModel, Exit1Located) {
  expect_model_error(GetParam(), "kite");
}

INSTANTIATE_TEST_SUITE_P(Kites, BadKiteModel, ::testing::ValuesIn(bad_kites()), label_name);

// A free body `plane` with wing points a, b, c around its centre and a bridle whose lines and
// knot follow; a tether from the ground to the knot unless `tethered` is false.
std::string bridle_model(const std::string& bridle, bool tethered = true) {
  return "gravity: [0, 0, -9.81]\n"
         "bodies:\n  plane: {mass: 36.8, inertia: [25, 32, 56], frame: free,\n"
         "          initial: {position: [0, 0, 50.5]},\n"
         "          points: {a: [1.2, 0, 0], b: [-0.6, 1, 0], c: [-0.6, -1, 0], d: [0, 0, 1]}}\n"
         "bridles:\n  bridle:\n" +
         bridle +
         (tethered ? "tethers:\n  main: {between: [[0, 0, 0], bridle.knot], segments: 2, length: "
                     "50, mass_per_length: 0.0046}\n"
                   : "");
}

std::vector<BadModel> bad_bridles() {
  const std::string lines = "    lines: [plane.a, plane.b, plane.c]\n";
  return {
      {"four lines",
       bridle_model("    lines: [plane.a, plane.b, plane.c, plane.d]\n    length: 1.3\n"
                    "    at: [0, 0, 50]\n"),
       "expected one to three lines in bridle 'bridle' (more would over-determine the knot), "
       "got 4"},
      {"knot off its lines", bridle_model(lines + "    length: 2\n    at: [0, 0, 50]\n"),
       "expected the knot of bridle 'bridle' at its line lengths from the points at t = 0: line "
       "1 to 'plane.a' has length 2"},
      {"lines in one plane",
       bridle_model("    lines: [plane.a, plane.b, plane.c]\n    length: [1.2, 1.1661903789690602, "
                    "1.1661903789690602]\n    at: [0, 0, 50.5]\n"),
       "expected lines of bridle 'bridle' in independent directions from the knot at t = 0 (two "
       "not parallel, three not in one plane), got three in one plane"},
      {"massless knot without a tether",
       bridle_model("    lines: [plane.a]\n    length: 1.3\n    at: [0, 0, 50]\n", false),
       "expected a tether ending at the knot 'bridle.knot' or a positive 'mass' in bridle "
       "'bridle'"},
      {"unknown line point",
       bridle_model("    lines: [plane.z]\n    length: 1\n    at: [0, 0, 50]\n"),
       "expected a point name for a line of bridle 'bridle', got 'plane.z'"},
      {"no length", bridle_model(lines + "    at: [0, 0, 50]\n"),
       "expected 'length' (of the lines) in bridle 'bridle', got none"},
  };
}

class BadBridleModel : public ::testing::TestWithParam<BadModel> {};

TEST_P(BadBridleModel, Exit1Located) {
  expect_model_error(GetParam(), "bridle");
}

INSTANTIATE_TEST_SUITE_P(Bridles, BadBridleModel, ::testing::ValuesIn(bad_bridles()), label_name);

// `derive` names the kite, its data source and the coefficients in use.
TEST(KiteDerive, ShowsTheAerodynamicModel) {
  ScratchDir dir("kite-derive");
  spit(dir.path() / "model.yaml", model("    body: plane\n    preset: ap2\n    elevator: 0.1\n"));
  const RunResult r = run_lagrange(dir.path(), {"derive", (dir.path() / "model.yaml").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Kite 'wing': rigid body 'plane', preset ap2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  CX = "), std::string::npos);
  EXPECT_NE(r.out.find("  Cn = "), std::string::npos);
  EXPECT_NE(r.out.find("  elevator = 1/10"), std::string::npos);
  EXPECT_NE(r.out.find("data: Ampyx AP2"), std::string::npos);
}

}  // namespace
}  // namespace lagrange::hardening
