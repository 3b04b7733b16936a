// Denavit–Hartenberg parameters in `links:` (src/elements/link_dh.cpp): the elbow manipulator
// written with standard and with modified DH equals the file written with origins, and the frames
// of spatial chains (revolute and prismatic joints, α = ±π/2, offsets θ and d) are the products
// of the DH matrices of each convention.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "support/ginac_values.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

/// The elbow manipulator in DH parameters: `a1`, `a2` the rows' a, `com1`, `com2` the centres of
/// mass in each link's frame (standard: at the far end of the link; modified: on its joint).
std::string dh_elbow(const std::string& convention, const std::string& a1, const std::string& a2,
                     const std::string& com1, const std::string& com2) {
  return fmt::format(R"(
parameters: {{m1: 1.0, m2: 0.8, L1: 1.0, L2: 1.0, Lc1: 0.5, Lc2: 0.4, I1: 0.08, I2: 0.05, g: 9.81}}
links:
  upper:
    joint: {{name: q1, type: revolute}}
    dh: {{convention: {0}, a: {1}}}
    mass: m1
    com: [{3}, 0, 0]
    inertia: [0, 0, I1]
  fore:
    parent: upper
    joint: {{name: q2, type: revolute}}
    dh: {{convention: {0}, a: {2}}}
    mass: m2
    com: [{4}, 0, 0]
    inertia: [0, 0, I2]
gravity: [0, -g, 0]
)",
                     convention, a1, a2, com1, com2);
}

/// Values of the parameters (their defaults) and of q, q̇ (random) of a model.
GiNaC::exmap state(const Model& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2);
  GiNaC::exmap at;
  for (const Parameter& p : m.parameters) at[p.sym] = p.value;
  for (const Coordinate& c : m.coordinates) {
    at[c.q] = u(rng);
    at[c.v] = u(rng);
  }
  return at;
}

void expect_same_elbow(const std::string& yaml) {
  const Model dh = read_model_string(yaml, "<dh>");
  const Model ref = read_model_file(testing::example_path("elbow_manipulator.yaml"));
  const Equations a = derive(dh), b = derive(ref);
  ASSERT_EQ(a.nv, 2u);
  for (unsigned seed : {1u, 2u, 3u}) {
    const GiNaC::exmap va = state(dh, seed), vb = state(ref, seed);
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_NEAR(value(a.h[i], va), value(b.h[i], vb), 1e-12) << i;
      for (size_t j = 0; j < 2; ++j)
        EXPECT_NEAR(value(a.M(i, j), va), value(b.M(i, j), vb), 1e-12) << i << j;
    }
  }
}

TEST(LinksDh, StandardElbowEqualsTheElbowManipulator) {
  expect_same_elbow(dh_elbow("standard", "L1", "L2", "Lc1 - L1", "Lc2 - L2"));
}

TEST(LinksDh, ModifiedElbowEqualsTheElbowManipulator) {
  expect_same_elbow(dh_elbow("modified", "0", "L1", "Lc1", "Lc2"));
}

// One DH row: a, α, d, θ and whether the joint is prismatic.
struct Row {
  double a, alpha, d, theta;
  bool prismatic;
};

const std::vector<Row> kRows = {{0.0, M_PI / 2, 0.3, 0.0, false},
                                {0.4, 0.0, 0.1, 0.2, false},
                                {0.0, -M_PI / 2, 0.2, 0.0, true}};

Eigen::Isometry3d rot(int axis, double angle) {
  return Eigen::Isometry3d(Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)));
}
Eigen::Isometry3d trans(int axis, double length) {
  return Eigen::Isometry3d(Eigen::Translation3d(length * Eigen::Vector3d::Unit(axis)));
}

std::string chain_yaml(const std::string& convention) {
  const char* alpha[] = {"pi/2", "0", "-pi/2"};
  std::string y = "links:\n";
  for (size_t i = 0; i < kRows.size(); ++i) {
    const Row& r = kRows[i];
    y += fmt::format(
        "  l{0}:\n    parent: {1}\n    joint: {{name: q{0}, type: {2}}}\n"
        "    dh: {{convention: {3}, a: {4}, alpha: {5}, d: {6}, theta: {7}}}\n"
        "    mass: 1\n    com: [0.1, 0.05, 0.02]\n    inertia: [0.01, 0.02, 0.025]\n"
        "    points: {{o: [0, 0, 0], p: [0.1, 0.2, 0.3]}}\n",
        i + 1, i == 0 ? "world" : "l" + std::to_string(i), r.prismatic ? "prismatic" : "revolute",
        convention, r.a, alpha[i], r.d, r.theta);
  }
  return y;
}

// The link frames follow T = Π A_i with the convention's A_i.
void expect_dh_frames(const std::string& convention) {
  const Model m = read_model_string(chain_yaml(convention), "<chain>");
  ASSERT_EQ(m.coordinates.size(), 3u);
  const GiNaC::exmap at = state(m, 9);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < kRows.size(); ++i) {
    const Row& r = kRows[i];
    const double q = value(m.coordinates[i].q, at);
    const double theta = r.theta + (r.prismatic ? 0 : q), d = r.d + (r.prismatic ? q : 0);
    T = convention == "standard"
            ? T * rot(2, theta) * trans(2, d) * trans(0, r.a) * rot(0, r.alpha)
            : T * rot(0, r.alpha) * trans(0, r.a) * rot(2, theta) * trans(2, d);
    for (const auto& [name, local] : {std::pair{"o", Eigen::Vector3d(0, 0, 0)},
                                      std::pair{"p", Eigen::Vector3d(0.1, 0.2, 0.3)}}) {
      const Eigen::Vector3d expected = T * local;
      const std::string point = "l" + std::to_string(i + 1) + "." + name;
      const Point* found = nullptr;
      for (const Point& p : m.points)
        if (p.name == point) found = &p;
      ASSERT_NE(found, nullptr) << point;
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(value(found->pos[static_cast<size_t>(k)], at), expected[k], 1e-13)
            << convention << " " << point << " " << k;
    }
  }
}

TEST(LinksDh, StandardFramesAreTheProductOfTheDhMatrices) {
  expect_dh_frames("standard");
}

TEST(LinksDh, ModifiedFramesAreTheProductOfTheDhMatrices) {
  expect_dh_frames("modified");
}

// The spatial chain moves and conserves energy in either convention.
TEST(LinksDh, SpatialChainConservesEnergy) {
  for (const std::string convention : {"standard", "modified"}) {
    auto sys = testing::load_string(chain_yaml(convention) + "gravity: [0, 0, -9.81]\n");
    const Trajectory tr = sys.run(testing::tight(sys, 1.0, 0.1));
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    const double e0 = tr.at(0, "energy"), e1 = tr.at(tr.rows() - 1, "energy");
    EXPECT_NEAR(e1, e0, 1e-8 * (1 + std::abs(e0))) << convention;
  }
}

}  // namespace
}  // namespace lagrange
