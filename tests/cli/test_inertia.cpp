// Degenerate inertias as a user meets them (issue 8, item 7): planar links given only I_zz, thin
// rods and point-like bodies are accepted where the motion allows them; a free body with a
// singular inertia, negative moments and the triangle inequality violated are model errors.
// Gravity acts on bodies.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// A two-link planar chain of posed bars, each with the given inertia.
std::string planar_chain(const std::string& inertia) {
  return "parameters: {m: 1, l: 1, g: 9.81}\ncoordinates:\n  q1: {initial: 0.5}\n  q2: {initial: "
         "0.2}\nbodies:\n  link1:\n    mass: m\n    inertia: " +
         inertia +
         "\n    position: rot_z(q1)*[l/2, 0, 0]\n    rotation: rot_z(q1)\n    points: {tip: [l/2, "
         "0, 0]}\n  link2:\n    mass: m\n    inertia: " +
         inertia +
         "\n    position: link1.tip + link1.R*rot_z(q2)*[l/2, 0, 0]\n    rotation: "
         "link1.R*rot_z(q2)\ngravity: [0, -g, 0]\nsimulate: {t_end: 1, rtol: 1e-10, atol: 1e-12}\n";
}

// The last row of a CSV.
std::string last_row(const fs::path& csv) {
  std::istringstream in(slurp(csv));
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

struct Outcome {
  RunResult result;
  std::vector<std::string> files;
  std::string last;
};

Outcome simulate(const std::string& label, const std::string& yaml) {
  ScratchDir dir("inertia-" + label);
  const fs::path model = dir.path() / "model.yaml", csv = dir.path() / "out.csv";
  spit(model, yaml);
  Outcome out;
  out.result = run_lagrange(dir.path(), {"simulate", model.string(), "-q", "-o", csv.string()});
  out.files = dir.files();
  out.last = last_row(csv);
  return out;
}

TEST(Inertia, PlanarLinksNeedOnlyIzz) {
  // Turning about z only, the links' T is ½ I_zz ω_z²: [0, 0, Izz] and the thin rod's
  // [0, Izz, Izz] give the same motion, bit for bit.
  const Outcome planar = simulate("planar", planar_chain("[0, 0, m*l^2/12]"));
  ASSERT_EQ(planar.result.exit_code, 0) << planar.result.err;
  const Outcome rod = simulate("rod", planar_chain("[0, m*l^2/12, m*l^2/12]"));
  ASSERT_EQ(rod.result.exit_code, 0) << rod.result.err;
  EXPECT_EQ(planar.last, rod.last);
  const Outcome point =
      simulate("point", planar_chain("[0, 0, 0]"));  // point masses at the centres
  EXPECT_EQ(point.result.exit_code, 0) << point.result.err;
  EXPECT_NE(point.last, planar.last);
}

TEST(Inertia, NonPhysicalMomentsAreModelErrors) {
  const Outcome triangle = simulate("triangle", planar_chain("[1, 1, 3]"));
  EXPECT_EQ(triangle.result.exit_code, 1);
  EXPECT_NE(triangle.result.err.find("model.yaml:6:3: error: body 'link1': non-physical inertia, "
                                     "principal moments (1, 1, 3) violate the triangle inequality"),
            std::string::npos)
      << triangle.result.err;
  EXPECT_EQ(triangle.files, std::vector<std::string>{"model.yaml"});
  const Outcome negative = simulate("negative", planar_chain("[0, 0, -1]"));
  EXPECT_EQ(negative.result.exit_code, 1);
  EXPECT_NE(negative.result.err.find("must be non-negative"), std::string::npos)
      << negative.result.err;
}

const std::string kFreeBar = R"(parameters: {m: 2, g: 9.81}
bodies:
  bar:
    mass: m
    inertia: INERTIA
    frame: free
    initial: {omega: [0, 0, 1]}
gravity: [0, 0, -g]
simulate: {t_end: 1, output_step: 0.5, rtol: 1e-12, atol: 1e-12}
)";

std::string free_bar(const std::string& inertia) {
  std::string s = kFreeBar;
  return s.replace(s.find("INERTIA"), 7, inertia);
}

TEST(Inertia, AFreeBodyNeedsAnInvertibleInertia) {
  const Outcome rod = simulate("free-rod", free_bar("[0, 0.1, 0.1]"));
  EXPECT_EQ(rod.result.exit_code, 1);
  EXPECT_NE(rod.result.err.find("model.yaml:3:3: error: body 'bar': a free body needs a "
                                "positive-definite inertia"),
            std::string::npos)
      << rod.result.err;
  EXPECT_EQ(rod.files, std::vector<std::string>{"model.yaml"});
}

TEST(Inertia, GravityActsOnBodies) {
  // A free bar dropped from rest: its origin falls by g t²/2 = 4.905 in the first second.
  const Outcome bar = simulate("falling", free_bar("[0.1, 0.1, 0.2]"));
  ASSERT_EQ(bar.result.exit_code, 0) << bar.result.err;
  std::istringstream row(bar.last);
  std::vector<double> values;
  for (std::string field; std::getline(row, field, ',');) values.push_back(std::stod(field));
  ASSERT_GE(values.size(), 4u);
  EXPECT_EQ(values[0], 1.0);                // t
  EXPECT_NEAR(values[3], -9.81 / 2, 1e-9);  // bar.z
}

}  // namespace
}  // namespace lagrange::hardening
