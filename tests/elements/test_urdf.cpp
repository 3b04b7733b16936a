// URDF robots (src/elements/urdf.cpp): the same arm as `links:`, inertial frames rotated by rpy,
// the UR5-like arm's Ḋ − 2C skew-symmetric at random states, `urdf:` in a model file, and
// located errors for broken files.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hardening/cli_runner.hpp"
#include "lagrange/manipulator.hpp"
#include "support/ginac_values.hpp"
#include "support/harness.hpp"
#include "support/test_paths.hpp"

namespace lagrange {
namespace {

const std::string kArm = std::string(LAGRANGE_SOURCE_DIR) + "/tests/elements/data/arm.urdf";
const std::string kUr5 = std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/ur5.urdf";

/// Values for every coordinate and velocity of `eq` (the same numbers for the same index).
GiNaC::exmap random_state(const Equations& eq, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2);
  GiNaC::exmap v;
  for (size_t i = 0; i < eq.nv; ++i) {
    v[eq.kin.q[i]] = u(rng);
    v[eq.kin.v[i]] = u(rng);
  }
  return v;
}

// The inertial frame of l1 is rotated by rpy (0.3, 0.2, 0.1); here its tensor is written already
// rotated into the link frame (R I Rᵀ, computed independently to 20 digits).
const char* kArmAsLinks = R"(gravity: [0, 0, -9.81]
links:
  l1:
    joint: {name: j1, type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, 0.5]}, damping: 0.1}
    mass: 2
    com: [0.2, 0, 0.05]
    inertia: [[0.010624456270346792471, 0.00011259035093747185953, 0.0033066224089734719671],
              [0.00011259035093747185953, 0.019417380803979968999, 0.00037649592492435262137],
              [0.0033066224089734719671, 0.00037649592492435262137, 0.02495816292567323853]]
  l2:
    parent: l1
    joint: {name: j2, type: revolute, axis: [0, 0, 1], origin: {xyz: [0.4, 0, 0], rpy: [pi/2, 0, 0]}}
    mass: 1
    com: [0.15, 0, 0]
    inertia: [0.001, 0.008, 0.008]
  tool:
    parent: l2
    joint: {type: fixed, origin: {xyz: [0.3, 0, 0]}}
    mass: 0.2
    inertia: [0.0001, 0.0001, 0.0001]
)";

TEST(Urdf, ArmEqualsTheSameArmWrittenAsLinks) {
  const Model urdf = read_model_file(kArm);
  const Model links = read_model_string(kArmAsLinks, "<links>");
  ASSERT_EQ(urdf.coordinates.size(), 2u);
  EXPECT_EQ(urdf.coordinates[0].name, "j1");
  const Equations a = derive(urdf), b = derive(links);
  for (unsigned seed : {1u, 2u, 3u}) {
    GiNaC::exmap va = random_state(a, seed), vb;
    for (size_t i = 0; i < 2; ++i) {
      vb[b.kin.q[i]] = va[a.kin.q[i]];
      vb[b.kin.v[i]] = va[a.kin.v[i]];
    }
    for (size_t i = 0; i < 2; ++i) {
      const double fa = value(a.h[i] + a.Q[i], va), fb = value(b.h[i] + b.Q[i], vb);
      EXPECT_NEAR(fa, fb, 1e-12 * (1 + std::abs(fb))) << "seed " << seed << ", row " << i;
      for (size_t j = 0; j < 2; ++j)
        EXPECT_NEAR(value(a.M(i, j), va), value(b.M(i, j), vb), 1e-13) << i << j;
    }
  }
}

// Ḋ − 2C is skew-symmetric and h = −C q̇ − g at random states of the six-axis arm.
TEST(Urdf, Ur5ManipulatorFormIsSkewSymmetricAtRandomStates) {
  const Model m = read_model_file(kUr5);
  ASSERT_EQ(m.coordinates.size(), 6u);
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  const GiNaC::matrix N = d_dot_minus_2c(f);
  for (unsigned seed : {11u, 12u}) {
    const GiNaC::exmap at = random_state(eq, seed);
    double scale = 0, worst = 0;
    for (size_t i = 0; i < 6; ++i)
      for (size_t j = 0; j < 6; ++j) {
        scale = std::max(scale, std::abs(value(N(i, j), at)));
        worst = std::max(worst, std::abs(value(N(i, j) + N(j, i), at)));
      }
    EXPECT_LT(worst, 1e-12 * scale) << "seed " << seed;
    for (size_t k = 0; k < 6; ++k) {
      GiNaC::ex r = eq.h[k] + f.g[k];
      for (size_t j = 0; j < 6; ++j) r += f.C(k, j) * eq.kin.v[j];
      EXPECT_NEAR(value(r, at), 0, 1e-10) << k;
    }
  }
}

TEST(Urdf, ModelFileAddsInitialStateTorquesAndGravity) {
  auto sys = testing::load_string(
      "parameters: {tau: 0.5}\n"
      "urdf: {file: '" +
      kArm +
      "', initial: {j2: 0.4}, rate: {j1: 0.1}}\n"
      "gravity: [0, 0, -9.81]\n"
      "generalized_forces: {j1: tau}\n");
  const Trajectory tr = sys.run(testing::tight(sys, 0.5, 0.05));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_DOUBLE_EQ(tr.at(0, "j2"), 0.4);
  EXPECT_DOUBLE_EQ(tr.at(0, "j1_dot"), 0.1);
  EXPECT_GT(tr.at(tr.rows() - 1, "j1_dot"), 0.2);  // the torque spins it up
}

}  // namespace
}  // namespace lagrange

namespace lagrange::hardening {
namespace {

struct BadUrdf {
  const char* label;
  std::string joint2, link2;
  const char* fragment;
  int line;
};

std::string urdf(const BadUrdf& b) {
  return "<robot name=\"r\">\n"                                            // 1
         "  <link name=\"base\"/>\n"                                       // 2
         "  <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/>"  // 3
         "<child link=\"a\"/></joint>\n"
         "  <link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" "  // 4
         "ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial></link>\n" +
         b.joint2 + "\n" + b.link2 + "\n</robot>\n";  // 5, 6
}

const std::string kLinkB =
    "  <link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" "
    "iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/></inertial></link>";

std::string joint(const std::string& type, const std::string& parent, const std::string& child,
                  const std::string& extra = "") {
  return "  <joint name=\"j2\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + extra + "</joint>";
}

std::vector<BadUrdf> bad_urdfs() {
  return {
      {"missing link", joint("revolute", "a", "c"), kLinkB,
       "expected the name of a <link> for the child of joint 'j2', got 'c' (missing link)", 5},
      {"cycle", joint("revolute", "a", "base"), kLinkB,
       "the joints form a cycle through joint 'j1' (link 'a' is not reachable from the root "
       "link 'b')",
       3},
      {"unsupported joint type", joint("floating", "a", "b"), kLinkB,
       "unsupported joint type 'floating' for joint 'j2'", 5},
      {"mimic joint", joint("revolute", "a", "b", "<mimic joint=\"j1\"/>"), kLinkB,
       "joint 'j2' mimics 'j1': mimic joints are not supported", 5},
      {"negative mass", joint("revolute", "a", "b"),
       "  <link name=\"b\"><inertial><mass value=\"-1\"/></inertial></link>",
       "expected a non-negative mass for link 'b', got -1", 6},
      {"non-physical inertia", joint("revolute", "a", "b"),
       "  <link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" "
       "iyy=\"1\" iyz=\"0\" izz=\"3\"/></inertial></link>",
       "body 'b': non-physical inertia", 6},
      // Mass-property and axis errors point at the offending element's own line.
      {"inertia on its own line", joint("revolute", "a", "b"),
       "  <link name=\"b\"><inertial><mass value=\"1\"/>\n    <inertia ixx=\"1\" ixy=\"0\" "
       "ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"3\"/></inertial></link>",
       "body 'b': non-physical inertia", 7},
      {"zero axis", joint("revolute", "a", "b", "\n    <axis xyz=\"0 0 0\"/>"), kLinkB,
       "expected a non-zero axis for joint 'j2', got [0, 0, 0]", 6},
      // Malformed XML is described in words, not as tinyxml2's error number.
      {"unclosed element", joint("revolute", "a", "b"),
       "  <link name=\"b\"><inertial><mass value=\"1\"/></link>",
       "expected well-formed XML: the element <inertial> is not closed before its parent's "
       "closing tag",
       6},
      {"unquoted attribute", joint("revolute", "a", "b"),
       "  <link name=\"b\"><inertial><mass value=1/></inertial></link>",
       "expected well-formed XML: a malformed attribute of <mass>", 6},
  };
}

class BadUrdfFile : public ::testing::TestWithParam<BadUrdf> {};

TEST_P(BadUrdfFile, ExitsOneWithTheFileAndLine) {
  const BadUrdf& bad = GetParam();
  ScratchDir dir(std::string("urdf-") + std::to_string(getpid()) + "-" +
                 std::to_string(reinterpret_cast<uintptr_t>(&bad) % 100000));
  spit(dir.path() / "robot.urdf", urdf(bad));
  const RunResult r = run_lagrange(dir.path(), {"simulate", (dir.path() / "robot.urdf").string(),
                                                "-o", (dir.path() / "out.csv").string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const std::string where =
      bad.line > 0 ? "robot.urdf:" + std::to_string(bad.line) + ":" : "robot.urdf:";
  EXPECT_NE(r.err.find(where), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(bad.fragment), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"robot.urdf"});
}

// A URDF given on its own is named after its <robot name>, and messages name its path as typed
// (relative to the working directory), as they do for model files.
TEST(UrdfFile, IsNamedAfterItsRobotAndItsPathPrintsAsTyped) {
  ScratchDir dir(std::string("urdf-name-") + std::to_string(getpid()));
  BadUrdf fine{"fine", joint("revolute", "a", "b"), kLinkB, "", 0};
  spit(dir.path() / "robot.urdf", urdf(fine));
  const std::string typed = fs::relative(dir.path() / "robot.urdf").string();  // from our cwd
  const RunResult ok =
      run_lagrange(dir.path(), {"simulate", typed, "-o", (dir.path() / "out.csv").string()});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(ok.out.rfind("r: ", 0), 0U) << ok.out;  // <robot name="r">, not the file's stem
  BadUrdf zero{"zero", joint("revolute", "a", "b", "<axis xyz=\"0 0 0\"/>"), kLinkB, "", 0};
  spit(dir.path() / "robot.urdf", urdf(zero));
  const RunResult bad =
      run_lagrange(dir.path(), {"simulate", typed, "-o", (dir.path() / "bad.csv").string()});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err.rfind(typed + ":5: error: expected a non-zero axis", 0), 0U) << bad.err;
}

INSTANTIATE_TEST_SUITE_P(Urdf, BadUrdfFile, ::testing::ValuesIn(bad_urdfs()), [](const auto& info) {
  std::string s = info.param.label;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
});

}  // namespace
}  // namespace lagrange::hardening
