// Bad kite input through the command line: exit code 1, a located message naming what is wrong,
// and no output file; and what `derive` shows of a kite's aerodynamic model.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

struct BadKite {
  const char* label;
  std::string kite;  ///< the lines under `kites: {wing: …}`
  const char* fragment;
};

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

std::vector<BadKite> bad_kites() {
  return {
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
  };
}

class BadKiteModel : public ::testing::TestWithParam<BadKite> {};

TEST_P(BadKiteModel, Exit1Located) {
  const BadKite& bad = GetParam();
  ScratchDir dir(std::string("kite-") + std::to_string(getpid()) + "-" +
                 std::to_string(reinterpret_cast<uintptr_t>(&bad) % 100000));
  spit(dir.path() / "model.yaml", model(bad.kite));
  const RunResult r = run_lagrange(dir.path(), {"simulate", (dir.path() / "model.yaml").string(),
                                                "-o", (dir.path() / "out.csv").string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("model.yaml:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(bad.fragment), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"model.yaml"});
}

INSTANTIATE_TEST_SUITE_P(Kites, BadKiteModel, ::testing::ValuesIn(bad_kites()),
                         [](const auto& info) {
                           std::string s = info.param.label;
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

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
