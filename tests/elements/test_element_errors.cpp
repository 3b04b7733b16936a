// Bad tether, winch, wind and link input through the command line: exit code 1, a located message
// naming what is wrong, and no output file.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

std::string tether(const std::string& fields) {
  return "gravity: [0, 0, -9.81]\ntethers:\n  t1:\n    between: [[0, 0, 0], free]\n" + fields;
}

const std::string kOk = "    segments: 4\n    length: 10\n    mass_per_length: 0.1\n";

std::vector<BadModel> bad_elements() {
  return {
      {"unknown point", "tethers:\n  t1:\n    between: [[0, 0, 0], nowhere]\n" + kOk,
       "expected a point name for the second end of tether 't1', got 'nowhere'"},
      {"zero segments", tether("    segments: 0\n    length: 10\n    mass_per_length: 0.1\n"),
       "expected a whole number of segments"},
      {"negative segments", tether("    segments: -3\n    length: 10\n    mass_per_length: 0.1\n"),
       "expected a whole number of segments"},
      {"zero length", tether("    segments: 4\n    length: 0\n    mass_per_length: 0.1\n"),
       "positive length"},
      {"negative mass", tether("    segments: 4\n    length: 10\n    mass_per_length: -1\n"),
       "expected a positive mass_per_length"},
      {"zero diameter", tether(kOk + "    drag: simple\n    diameter: 0\n"),
       "expected a positive diameter"},
      {"drag without diameter", tether(kOk + "    drag: simple\n"), "expected 'diameter'"},
      {"unknown drag model", tether(kOk + "    drag: heavy\n"),
       "expected 'none', 'simple' or 'fine'"},
      {"elasticity not a map", tether(kOk + "    elasticity: 5\n"),
       "expected a map for the elasticity of tether 't1' ({EA, damping}), got '5'"},
      {"zero EA", tether(kOk + "    elasticity: {EA: 0}\n"),
       "expected a positive EA of the elasticity of tether 't1', got 0"},
      {"elasticity without EA", tether(kOk + "    elasticity: {damping: 3}\n"),
       "expected 'EA' in the elasticity of tether 't1', got none"},
      {"negative elastic damping", tether(kOk + "    elasticity: {EA: 10, damping: -1}\n"),
       "expected a non-negative damping of the elasticity of tether 't1', got -1"},
      {"unknown elasticity key", tether(kOk + "    elasticity: {EA: 10, stiffness: 3}\n"),
       "unknown key 'stiffness' in the elasticity of tether 't1', expected one of: EA, damping"},
      {"ends too far apart", "tethers:\n  t1:\n    between: [[0, 0, 0], [20, 0, 0]]\n" + kOk,
       "at most its length"},
      {"winch without tether",
       tether(kOk) + "winches:\n  w:\n    radius: 0.1\n    inertia: 1\n"
                     "    initial: {reeled_out: 5}\n",
       "expected 'tether'"},
      {"winch of an unknown tether",
       tether(kOk) + "winches:\n  w:\n    tether: t2\n    radius: 0.1\n    inertia: 1\n"
                     "    initial: {reeled_out: 5}\n",
       "expected the name of a tether for winch 'w', got 't2'"},
      {"roughness zero", tether(kOk) + "wind: {profile: logarithmic, speed: 5, roughness: 0}\n",
       "expected a positive roughness length z0"},
      {"roughness negative",
       tether(kOk) + "wind: {profile: logarithmic, speed: 5, roughness: -0.1}\n",
       "expected a positive roughness length z0"},
      {"roughness above the reference height",
       tether(kOk) + "wind: {profile: logarithmic, speed: 5, reference_height: 0.05}\n",
       "expected a roughness length z0 below the reference height, got z0 = 0.1 and reference "
       "height 0.05"},
      {"roughness at the reference height",
       tether(kOk) + "wind: {profile: logarithmic, speed: 5, roughness: 2, reference_height: 2}\n",
       "expected a roughness length z0 below the reference height, got z0 = 2"},
      {"power-law exponent of 100",
       tether(kOk) + "wind: {profile: power_law, speed: 5, exponent: 100}\n",
       "expected a power-law exponent between 0 and 1"},
      {"unknown wind profile", tether(kOk) + "wind: {profile: gusty, speed: 5}\n",
       "expected 'uniform', 'logarithmic' or 'power_law'"},
  };
}

std::string arm(const std::string& second) {
  return "links:\n  a:\n    joint: {name: q1, type: revolute}\n    mass: 1\n"
         "    inertia: [0, 0, 0.1]\n" +
         second;
}

std::vector<BadModel> bad_links() {
  const std::string body = "    mass: 1\n    inertia: [0, 0, 0.1]\n";
  return {
      {"unknown parent", arm("  b:\n    parent: c\n    joint: {name: q2, type: revolute}\n" + body),
       "expected 'world' or a link written before link 'b' as its parent, got 'c' (links before "
       "it: a)"},
      {"parent written later",
       "links:\n  b:\n    parent: a\n    joint: {name: q2, type: revolute}\n" + body +
           "  a:\n    joint: {name: q1, type: revolute}\n" + body,
       "got 'a' (links before it: none)"},
      {"unknown joint type",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: spherical}\n" + body),
       "expected revolute, continuous, prismatic or fixed for the type of the joint of link 'b', "
       "got 'spherical'"},
      {"joint without name", arm("  b:\n    parent: a\n    joint: {type: revolute}\n" + body),
       "expected 'name' (its coordinate's name) in the joint of link 'b'"},
      {"fixed joint with a name",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: fixed}\n" + body),
       "expected no 'name' in the joint of link 'b': a fixed joint has no coordinate"},
      {"zero axis",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute, axis: [0, 0, 0]}\n" + body),
       "expected a non-zero axis for joint 'q2'"},
      {"joint name taken",
       arm("  b:\n    parent: a\n    joint: {name: q1, type: revolute}\n" + body),
       "expected a unique name, got coordinate 'q1' which is already the coordinate"},
      {"negative mass",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute}\n    mass: -1\n"
           "    inertia: [0, 0, 0.1]\n"),
       "expected a positive mass for link 'b', got -1"},
      {"non-physical inertia",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: prismatic, axis: [1, 0, 0]}\n"
           "    mass: 1\n    inertia: [1, 1, 3]\n"),
       "body 'b': non-physical inertia"},
      {"negative damping",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute, damping: -1}\n" + body),
       "expected a non-negative damping of joint q2, got -1"},
      {"torque of an unknown name",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute, torque: -k*q2}\n" + body),
       "unknown name 'k' (in torque of joint 'q2')"},
      {"dh without convention",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute}\n    dh: {a: 1}\n" + body),
       "expected 'convention: standard' or 'convention: modified' in dh of link 'b'"},
      {"dh of an unknown convention",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute}\n"
           "    dh: {convention: craig, a: 1}\n" +
           body),
       "expected standard or modified for the convention of dh of link 'b', got 'craig'"},
      {"dh beside an origin",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute, origin: {xyz: [1, 0, 0]}}\n"
           "    dh: {convention: standard, a: 1}\n" +
           body),
       "expected no 'origin' in the joint of link 'b': its 'dh' places the joint (axis z)"},
      {"dh with an unknown key",
       arm("  b:\n    parent: a\n    joint: {name: q2, type: revolute}\n"
           "    dh: {convention: standard, r: 1}\n" +
           body),
       "'r'"},
  };
}

class BadElementModel : public ::testing::TestWithParam<BadModel> {};

TEST_P(BadElementModel, Exit1Located) {
  expect_model_error(GetParam(), "element");
}

INSTANTIATE_TEST_SUITE_P(Elements, BadElementModel, ::testing::ValuesIn(bad_elements()),
                         label_name);
INSTANTIATE_TEST_SUITE_P(Links, BadElementModel, ::testing::ValuesIn(bad_links()), label_name);

}  // namespace
}  // namespace lagrange::hardening

namespace lagrange::hardening {
namespace {

// `derive` shows what a tether and a winch lowered into the model, one segment's terms.
TEST(ElementDerive, ShowsOneSegmentAndTheDrum) {
  ScratchDir dir("element-derive");
  const RunResult r = run_lagrange(
      dir.path(), {"derive", std::string(LAGRANGE_SOURCE_DIR) + "/examples/winch.yaml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Tether 'line': 10 segments, lumped model, varying length"),
            std::string::npos);
  EXPECT_NE(r.out.find("  l_s = 1/10*drum.reeled_out"), std::string::npos) << r.out.substr(0, 800);
  EXPECT_NE(r.out.find("  C_1 = "), std::string::npos);
  EXPECT_EQ(r.out.find("  C_2 = "), std::string::npos);
  EXPECT_NE(r.out.find("Winch 'drum' reeling tether 'line'"), std::string::npos);
  EXPECT_NE(r.out.find("  T_drum = "), std::string::npos);
}

}  // namespace
}  // namespace lagrange::hardening
