// A vector constraint whose component is identically zero (a planar loop closure's z) drops
// that component with a note instead of failing on a rank-deficient Jacobian (issue 36 item 8):
// a four-bar linkage closed by `loop: B - C` runs as the same linkage closed by two scalars.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// Crank l1 at the origin, coupler l2, rocker l3 pivoted at (d, 0); masses at the crank's tip,
// the coupler's middle and the rocker's tip; the crank starts at 1.2 rad turning at 1 rad/s.
const std::string kFourBar = R"(name: four-bar
parameters: {l1: 1, l2: 2.5, l3: 2, d: 2, m: 1}
coordinates:
  th1: {initial: 1.2, rate: 1, fixed: true}
  th2: {initial: 0.3}
  th3: {initial: 1.9}
points:
  A: [l1*cos(th1), l1*sin(th1), 0]
  B: [l1*cos(th1) + l2*cos(th2), l1*sin(th1) + l2*sin(th2), 0]
  C: [d + l3*cos(th3), l3*sin(th3), 0]
  G2: [l1*cos(th1) + l2/2*cos(th2), l1*sin(th1) + l2/2*sin(th2), 0]
particles: {A: m, G2: m, C: m}
constraints:
LOOP
simulate: {t_end: 2, output_step: 0.1}
)";

std::string with_loop(const std::string& loop) {
  std::string text = kFourBar;
  text.replace(text.find("LOOP"), 4, loop);
  return text;
}

// Rows of a CSV as numbers, and its header.
std::vector<std::vector<double>> rows(const fs::path& path, std::vector<std::string>& header) {
  std::istringstream in(slurp(path));
  std::string line, field;
  std::getline(in, line);
  for (std::istringstream h(line); std::getline(h, field, ',');) header.push_back(field);
  std::vector<std::vector<double>> out;
  while (std::getline(in, line)) {
    std::vector<double> row;
    for (std::istringstream r(line); std::getline(r, field, ',');)
      row.push_back(std::strtod(field.c_str(), nullptr));
    if (!row.empty()) out.push_back(row);
  }
  return out;
}

TEST(PlanarConstraint, VectorLoopClosureRunsAsTheScalarOnes) {
  ScratchDir dir("planar-four-bar");
  const fs::path vec = dir.path() / "vector.yaml", sc = dir.path() / "scalar.yaml";
  spit(vec, with_loop("  loop: B - C"));
  spit(sc, with_loop("  loop_x: B.x - C.x\n  loop_y: B.y - C.y"));
  const fs::path a = dir.path() / "a.csv", b = dir.path() / "b.csv";
  const RunResult rv = run_lagrange(dir.path(), {"simulate", vec.string(), "-q", "-o", a.string()});
  ASSERT_EQ(rv.exit_code, 0) << rv.err;
  EXPECT_NE(rv.err.find(vec.string() +
                        ":14:3: note: 'loop.z' of constraint 'loop' is identically zero (a "
                        "planar constraint): dropped"),
            std::string::npos)
      << rv.err;
  const RunResult rs = run_lagrange(dir.path(), {"simulate", sc.string(), "-q", "-o", b.string()});
  ASSERT_EQ(rs.exit_code, 0) << rs.err;
  std::vector<std::string> hv, hs;
  const auto tv = rows(a, hv), ts = rows(b, hs);
  ASSERT_EQ(hv.size(), hs.size());
  EXPECT_EQ(hv[10], "loop.x");
  EXPECT_EQ(hs[10], "loop_x");
  ASSERT_EQ(tv.size(), 21u);
  EXPECT_EQ(tv, ts);  // the same equations: the same numbers, multipliers included
  // The loop stays closed: B = C at every sample (l1, l2, l3, d = 1, 2.5, 2, 2).
  for (const auto& r : tv) {
    const double th1 = r[1], th2 = r[2], th3 = r[3];
    EXPECT_NEAR(std::cos(th1) + 2.5 * std::cos(th2), 2 + 2 * std::cos(th3), 1e-9) << r[0];
    EXPECT_NEAR(std::sin(th1) + 2.5 * std::sin(th2), 2 * std::sin(th3), 1e-9) << r[0];
  }
}

TEST(PlanarConstraint, AConstraintZeroInEveryComponentIsAnError) {
  ScratchDir dir("planar-zero");
  const fs::path model = dir.path() / "zero.yaml";
  spit(model, with_loop("  loop_x: B.x - C.x\n  loop_y: B.y - C.y\n  nothing: A - A"));
  const RunResult r = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(model.string() + ":16:3: error: expected a constraint that constrains "
                                        "something, got 'nothing', identically zero"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
