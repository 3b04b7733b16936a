// `lagrange derive` of a large model, as a user meets it: the 50-link pendulum (4.9 MB of text
// written out in full) is printed through named common subexpressions, says so and how to get
// the full expansion; small models are printed in full as before.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace {

using lagrange::hardening::run_lagrange;
using lagrange::hardening::ScratchDir;
using lagrange::hardening::spit;

// The benchmark family (bench/n_link_pendulum.cpp): absolute angles, per-link masses and lengths.
std::string n_link_pendulum(int n) {
  std::string y = "name: " + std::to_string(n) + "-link pendulum\nparameters: {";
  for (int k = 1; k <= n; ++k)
    y += "m" + std::to_string(k) + ": " + std::to_string(1.0 + 0.1 * (k % 7)) + ", l" +
         std::to_string(k) + ": " + std::to_string(0.5 + 0.05 * (k % 5)) + ", ";
  y += "g: 9.81}\ncoordinates:\n";
  for (int k = 1; k <= n; ++k) y += "  th" + std::to_string(k) + ": {initial: 0.3}\n";
  y += "points:\n";
  for (int k = 1; k <= n; ++k) {
    const std::string K = std::to_string(k);
    y += "  p" + K + ": " + (k > 1 ? "p" + std::to_string(k - 1) + " + " : "") + "[l" + K +
         "*sin(th" + K + "), -l" + K + "*cos(th" + K + "), 0]\n";
  }
  y += "particles: {";
  for (int k = 1; k <= n; ++k)
    y += (k > 1 ? ", p" : "p") + std::to_string(k) + ": m" + std::to_string(k);
  return y + "}\ngravity: [0, -g, 0]\n";
}

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

TEST(CliDerive, LargeModelIsPrintedThroughCommonSubexpressions) {
  ScratchDir dir("derive-large");
  spit(dir.path() / "chain.yaml", n_link_pendulum(50));
  const auto r = run_lagrange(dir.path(), {"derive", (dir.path() / "chain.yaml").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Large model"), std::string::npos) << r.out.substr(0, 500);
  EXPECT_NE(r.out.find("named common subexpressions"), std::string::npos);
  EXPECT_NE(r.out.find("lagrange derive --expand"), std::string::npos);
  EXPECT_LT(r.out.size(), 400000u);                    // the full expansion is 4.9 MB
  EXPECT_EQ(count(r.out, "\n  M_{"), 50u * 51u / 2u);  // every entry of the lower triangle
  EXPECT_NE(r.out.find("\n  M_{50,50} = "), std::string::npos);
  EXPECT_NE(r.out.find("\n  (h+Q)_{th50} = "), std::string::npos);
  EXPECT_NE(r.out.find("\n  x1 = "), std::string::npos);
  EXPECT_NE(r.out.find("\n  T = "), std::string::npos);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"chain.yaml"});

  const auto json = run_lagrange(
      dir.path(), {"derive", (dir.path() / "chain.yaml").string(), "--format", "json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"form\": \"common_subexpressions\""), std::string::npos);
}

TEST(CliDerive, SmallModelIsPrintedInFullWithOrWithoutExpand) {
  ScratchDir dir("derive-small");
  const std::string model = std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml";
  const auto plain = run_lagrange(dir.path(), {"derive", model});
  const auto expanded = run_lagrange(dir.path(), {"derive", model, "--expand"});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(expanded.exit_code, 0) << expanded.err;
  EXPECT_EQ(plain.out.find("Large model"), std::string::npos);
  EXPECT_NE(plain.out.find("Euler-Lagrange equations"), std::string::npos);
  // The same sections with as many equations each (GiNaC's term order may differ between
  // processes, so the expressions themselves are not compared).
  auto outline = [](const std::string& text) {
    std::vector<std::string> shape;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      shape.push_back(line.rfind("  ", 0) == 0 ? "equation" : line);
    return shape;
  };
  EXPECT_EQ(outline(plain.out), outline(expanded.out));
}

TEST(CliDerive, ExpandForcesTheFullExpansion) {
  ScratchDir dir("derive-expand");
  spit(dir.path() / "chain.yaml", n_link_pendulum(30));
  const auto r =
      run_lagrange(dir.path(), {"derive", (dir.path() / "chain.yaml").string(), "--expand"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("Large model"), std::string::npos);
  EXPECT_NE(r.out.find("Euler-Lagrange equations"), std::string::npos);
  EXPECT_GT(r.out.size(), 1000000u);
}

}  // namespace

// Issue 20, item 1: a spatial R-R-P arm with named parameters hung in the solved accelerations
// (GiNaC's symbolic inverse, deep in polynomial gcd). Solving is budgeted by expression size now:
// the arm prints M and h + Q and says why the accelerations are not solved, in well under the
// harness's limit; a small model still gets them.
TEST(CliDerive, SpatialArmWithParametersFinishesAndSaysWhyAccelerationsAreNotSolved) {
  ScratchDir dir("derive-rrp");
  spit(dir.path() / "rrp.yaml", R"(name: rrp arm
parameters: {g: 9.81, m1: 3.0, m2: 2.0, m3: 1.2, h1: 0.4, h2: 0.3, L2: 0.5, c2: 0.25, e3: 0.05}
links:
  base:   {joint: {name: q1, type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, h1]}, initial: 0.2, rate: 0.5},
           mass: m1, com: [0, 0, 0.1], inertia: [0.03, 0.03, 0.02]}
  upper:  {parent: base, joint: {name: q2, type: revolute, axis: [0, 1, 0], origin: {xyz: [0, 0, h2]}, initial: -0.4, rate: 0.1},
           mass: m2, com: [c2, 0, 0], inertia: [0.004, 0.045, 0.046]}
  slider: {parent: upper, joint: {name: d3, type: prismatic, axis: [1, 0, 0], origin: {xyz: [L2, e3, 0]}, initial: 0.1, rate: -0.2},
           mass: m3, com: [0.1, 0, 0.02], inertia: [[0.002, 0.0003, 0.0001], [0.0003, 0.011, 0.0002], [0.0001, 0.0002, 0.012]]}
gravity: [0, 0, -g]
)");
  for (const std::string format : {"text", "latex"}) {
    const auto start = std::chrono::steady_clock::now();
    const auto r =
        lagrange::hardening::Child(
            dir.path(), {"derive", (dir.path() / "rrp.yaml").string(), "--format", format})
            .wait(std::chrono::seconds(60));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.exit_code, 0) << format << ": " << r.err;
    EXPECT_LT(seconds, 30.0) << format;  // was > 25 min; about 0.2 s here
    EXPECT_NE(r.out.find("not solved symbolically"), std::string::npos) << format;
    EXPECT_NE(r.out.find("M_{33}"), std::string::npos) << format;
    EXPECT_LT(r.out.size(), 200000u) << format;
  }
}

TEST(CliDerive, SmallModelsStillGetTheirSolvedAccelerations) {
  const std::string examples = std::string(LAGRANGE_SOURCE_DIR) + "/examples/";
  ScratchDir dir("derive-small");
  const auto r = run_lagrange(dir.path(), {"derive", examples + "elastic_pendulum.yaml"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Accelerations a = M^-1 (h + Q)\n  l_ddot = "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("not solved symbolically"), std::string::npos);
}

// Issue 20, item 9: an option that would be ignored is a usage error, before anything runs.
TEST(CliDerive, PlotColumnsWithoutPlotIsAUsageError) {
  ScratchDir dir("plot-columns");
  const std::string model = std::string(LAGRANGE_SOURCE_DIR) + "/examples/pendulum.yaml";
  const auto r = run_lagrange(dir.path(), {"simulate", model, "-o", (dir.path() / "p.csv").string(),
                                           "--plot-columns", "theta"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--plot FILE"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "p.csv"));
}

// Issue 20, items 3 and 5, as a user meets them: a winch's initial reel rate is kept (the free
// tether's nodes start stretching with it, no projection note), `fixed: true` is accepted in a
// winch's `initial`, a tether strung between two supports starts on its constraints (no note),
// and -q prints nothing on a run that succeeds.
TEST(CliDerive, WinchRateIsKeptAndTethersBetweenSupportsStartQuietly) {
  ScratchDir dir("winch-rate");
  spit(dir.path() / "winch.yaml", R"(name: winch rate
parameters: {R: 0.2, J: 0.05, mu: 0.4, L: 30, g: 9.81}
gravity: [0, 0, -g]
winches:
  drum: {tether: line, radius: R, inertia: J, total_length: L,
         initial: {reeled_out: 3, rate: 0.5, fixed: true}}
tethers:
  line: {between: [[0, 0, 0], free], segments: 6, mass_per_length: mu}
simulate: {t_end: 0.2, output_step: 0.1}
)");
  auto r = run_lagrange(dir.path(), {"simulate", (dir.path() / "winch.yaml").string(), "-o",
                                     (dir.path() / "w.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("note:"), std::string::npos) << r.err;
  std::istringstream csv(lagrange::hardening::slurp(dir.path() / "w.csv"));
  std::string header, first;
  std::getline(csv, header);
  std::getline(csv, first);
  std::vector<std::string> names, values;
  for (std::istringstream h(header), v(first);;) {
    std::string a, b;
    if (!std::getline(h, a, ',') || !std::getline(v, b, ',')) break;
    names.push_back(a);
    values.push_back(b);
  }
  const auto at = std::find(names.begin(), names.end(), "drum.reeled_out_dot");
  ASSERT_NE(at, names.end());
  EXPECT_DOUBLE_EQ(std::stod(values[static_cast<size_t>(at - names.begin())]), 0.5);

  spit(dir.path() / "span.yaml", R"(name: span
parameters: {g: 9.81}
gravity: [0, 0, -g]
tethers:
  line: {between: [[0, 0, 0], [8, 0, 1]], segments: 7, length: 10, mass_per_length: 0.3}
simulate: {t_end: 0.2, output_step: 0.1}
)");
  r = run_lagrange(dir.path(), {"simulate", (dir.path() / "span.yaml").string(), "-o",
                                (dir.path() / "s.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("note:"), std::string::npos) << r.err;
  r = run_lagrange(dir.path(), {"simulate", (dir.path() / "span.yaml").string(), "-q", "-o",
                                (dir.path() / "s.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out + r.err, "");
}
