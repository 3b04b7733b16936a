// An optimisation study (src/cli/optimal_sweep.cpp, docs/sweeps.md "Optimal control: a power
// curve"): the cases run outwards from the model file's own values, each started from the
// nearest solved case; `lagrange sweep --optimize` on a rotor in the wind (tests/cli/data/
// wind_rotor.yaml) gives the power curve of its closed form, a warm-started case reaches the cold
// solve's optimum in fewer iterations, and a case that cannot be solved is recorded while the
// curve goes on.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "cli/optimal_sweep.hpp"
#include "hardening/cli_runner.hpp"
#include "lagrange/io.hpp"
#include "support/test_paths.hpp"

namespace lagrange::cli {
namespace {

std::vector<sweep::Case> line(const std::vector<double>& values) {
  std::vector<sweep::Case> cases;
  for (size_t i = 0; i < values.size(); ++i) cases.push_back({i, {{"W", values[i]}}});
  return cases;
}

std::vector<size_t> all(size_t n) {
  std::vector<size_t> v;
  for (size_t i = 0; i < n; ++i) v.push_back(i);
  return v;
}

TEST(OptimalSweepOrder, OneParameterRunsOutwardsFromTheFilesValue) {
  // W = 5 … 15 on a file with W = 10: 10, then down to 5 (ties go to the lower case), then up.
  const auto cases = line({5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15});
  const std::vector<size_t> order = warm_start_order(cases, all(11), {10.0});
  EXPECT_EQ(order, (std::vector<size_t>{5, 4, 3, 2, 1, 0, 6, 7, 8, 9, 10}));
  // Every case after the first is beside one already run: its start is its neighbour.
  for (size_t k = 1; k < order.size(); ++k) {
    const std::vector<size_t> before(order.begin(), order.begin() + static_cast<long>(k));
    const std::optional<size_t> from = nearest_case(cases, order[k], before);
    ASSERT_TRUE(from.has_value());
    EXPECT_EQ(std::abs(static_cast<long>(*from) - static_cast<long>(order[k])), 1) << k;
  }
  // A file value outside the range starts at the nearer end.
  EXPECT_EQ(warm_start_order(cases, all(11), {20.0}).front(), 10u);
  EXPECT_EQ(nearest_case(cases, 3, {}), std::nullopt);
}

TEST(OptimalSweepOrder, AResumedStudyContinuesFromTheCasesItRan) {
  // Cases 4 … 6 ran before: the pending cases continue from them, nearest first.
  const auto cases = line({5, 6, 7, 8, 9, 10, 11});
  const std::vector<size_t> order = warm_start_order(cases, {0, 1, 2, 3}, {10.0}, {4, 5, 6});
  EXPECT_EQ(order, (std::vector<size_t>{3, 2, 1, 0}));
}

TEST(OptimalSweepOrder, AGridFillsOutwardsInUnitsOfEachSpan) {
  // W 6 … 10 (span 4) and L 100 … 300 (span 200): L's step of 100 is half a span, W's step of 2
  // half a span too, so every case is one step from one run before it: from (8, 200) the
  // lowest-numbered such case each time.
  std::vector<sweep::Case> cases;
  for (double w : {6.0, 8.0, 10.0})
    for (double l : {100.0, 200.0, 300.0}) cases.push_back({cases.size(), {{"W", w}, {"L", l}}});
  const std::vector<size_t> order = warm_start_order(cases, all(9), {8.0, 200.0});
  EXPECT_EQ(order.front(), 4u);  // (8, 200)
  EXPECT_EQ(order, (std::vector<size_t>{4, 1, 0, 2, 3, 5, 6, 7, 8}));
  // The corner (10, 300) starts from an edge case one step away, not from the centre.
  const std::optional<size_t> from = nearest_case(cases, 8, {4, 5, 7});
  ASSERT_TRUE(from.has_value());
  EXPECT_TRUE(*from == 5 || *from == 7) << *from;
}

TEST(OptimalSweepOrder, GridNeighboursAreTheAdjacentValuesOfOneParameter) {
  const std::vector<std::vector<size_t>> n = grid_neighbours(line({8, 4, 6, 10}));
  EXPECT_EQ(n[0], (std::vector<size_t>{2, 3}));  // 8: 6 below, 10 above
  EXPECT_EQ(n[1], (std::vector<size_t>{2}));     // 4: the lowest
  EXPECT_EQ(n[3], (std::vector<size_t>{0}));
  std::vector<sweep::Case> grid;
  for (double w : {6.0, 8.0})
    for (double l : {100.0, 200.0, 300.0}) grid.push_back({grid.size(), {{"W", w}, {"L", l}}});
  // (6, 200): (8, 200) above in W; (6, 100) and (6, 300) in L; not the diagonal (8, 100).
  EXPECT_EQ(grid_neighbours(grid)[1], (std::vector<size_t>{4, 0, 2}));
}

namespace fs = std::filesystem;
using hardening::run_lagrange;
using hardening::RunResult;
using hardening::ScratchDir;
using hardening::slurp;

const std::string kRotor = std::string(LAGRANGE_SOURCE_DIR) + "/tests/cli/data/wind_rotor.yaml";

using Row = std::map<std::string, std::string>;

// The summary's rows by column name (the `reason` field, which may hold commas, is quoted).
std::vector<Row> read_summary(const fs::path& path) {
  const auto fields = [](const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        out.emplace_back();
      } else {
        out.back() += c;
      }
    }
    return out;
  };
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = fields(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = fields(line);
    Row row;
    for (size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

// The rotor's best mean power at wind W (the file's header): steady, u = k (W − r w)² ≤ 40, the
// power u w − c u² maximised over the rotor speed w ≥ 1 by golden-section search on the branch
// where u is free, or at u = 40 when that bound holds (w = W − √(40/k)).
double rotor_power(double W) {
  const double k = 0.5, r = 1.0, c = 0.002, umax = 40;
  const auto power = [&](double w) {
    const double u = k * (W - r * w) * (W - r * w);
    return u * w - c * u * u;
  };
  double a = std::max(1.0, (W - std::sqrt(umax / k)) / r), b = W / r;  // where u ≤ umax
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    if (power(x1) < power(x2)) {
      a = x1;
    } else {
      b = x2;
    }
  }
  return power((a + b) / 2);
}

TEST(OptimalSweep, TheRotorsPowerCurveIsItsClosedFormAndACaseThatCannotBeSolvedIsRecorded) {
  ScratchDir dir("optimal_sweep");
  const fs::path study = dir.path() / "curve";
  // W = 0.5 is below the cut-in wind (the rotor cannot hold w ≥ 1): infeasible, run last on
  // its side after the cases from the file's W = 8 down.
  const RunResult r = run_lagrange(
      dir.path(), {"sweep", kRotor, "--optimize", "--vary", "W=0.5,4,6,8,10,12,14,16", "--metric",
                   "u_max=max(u)", "--keep-trajectories", "-o", study.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(study / "summary.csv");
  ASSERT_EQ(rows.size(), 8u);
  // The failed case is recorded with Ipopt's reason, and the curve beyond it is complete.
  EXPECT_EQ(rows[0].at("status"), "failed");
  EXPECT_NE(rows[0].at("reason").find("infeasib"), std::string::npos) << rows[0].at("reason");
  EXPECT_TRUE(fs::exists(study / "case_0.csv"));  // what it computed is kept
  double previous = 0.0;
  for (size_t i = 1; i < rows.size(); ++i) {
    const Row& row = rows[i];
    ASSERT_EQ(row.at("status"), "ok") << i << " " << row.at("reason");
    const double W = std::stod(row.at("W")), P = std::stod(row.at("objective"));
    // The closed form, to the solver's tolerance: the steady optimum is exact in collocation.
    EXPECT_NEAR(P, rotor_power(W), 1e-6 * rotor_power(W)) << "W = " << W;
    EXPECT_GT(P, previous) << "W = " << W;  // monotone
    previous = P;
    // Every case but the file's own value started from a neighbour's solution (case 3, W = 8).
    if (i == 3) {
      EXPECT_EQ(row.at("warm_start"), "");
    } else {
      const size_t from = std::stoul(row.at("warm_start"));
      EXPECT_EQ(from, i < 3 ? i + 1 : i - 1) << "W = " << W;
    }
  }
  // Below the generator's bound (u < 40, up to W = 12) the power grows like W³: at c = 0 it
  // would be 4 k W³ / (27 r); the copper loss c u² takes at most 3 % of it here.
  for (size_t i = 1; i <= 5; ++i) {
    const double W = std::stod(rows[i].at("W")), P = std::stod(rows[i].at("objective"));
    EXPECT_LT(std::stod(rows[i].at("u_max")), 40 - 1e-3);
    EXPECT_NEAR(P / (4 * 0.5 * W * W * W / 27), 1.0, 0.03) << "W = " << W;
  }
  // Above it the bound holds and the power grows about linearly.
  EXPECT_NEAR(std::stod(rows[7].at("u_max")), 40, 1e-6);
}

// The point-mass kite's power cycle has several local optima: started outwards from W = 10, each
// wind is solved again from its neighbours' solutions and keeps the better optimum, so the power
// curve comes out monotone in the wind (issue 35). An improved case names the neighbour whose
// solution gave it and the objective it had before, which it beats.
TEST(OptimalSweep, TheKitesPowerCurveIsMonotoneInTheWind) {
  ScratchDir dir("optimal_kite");
  const fs::path study = dir.path() / "curve";
  const RunResult r = run_lagrange(
      dir.path(),
      {"sweep", std::string(LAGRANGE_SOURCE_DIR) + "/examples/optimal/power_cycle_pointmass.yaml",
       "--optimize", "--vary", "W=6:10:5", "--intervals", "20", "-o", study.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(study / "summary.csv");
  ASSERT_EQ(rows.size(), 5u);
  double previous = 0.0;
  for (const Row& row : rows) {
    ASSERT_EQ(row.at("status"), "ok") << row.at("reason");
    const double P = std::stod(row.at("objective"));
    EXPECT_GT(P, previous) << "W = " << row.at("W");
    previous = P;
    const std::string& reason = row.at("reason");
    const std::string before = "(objective before: ";
    if (const size_t at = reason.find(before); at != std::string::npos) {
      EXPECT_EQ(reason.find("improved from case " + row.at("warm_start") + "'s solution"), 0u)
          << reason;
      EXPECT_GT(P, std::stod(reason.substr(at + before.size()))) << reason;
    }
  }
}

TEST(OptimalSweep, AWarmStartedCaseReachesTheColdOptimumInFewerIterations) {
  ScratchDir dir("optimal_warm");
  const fs::path study = dir.path() / "curve";
  const RunResult r = run_lagrange(
      dir.path(), {"sweep", kRotor, "--optimize", "--vary", "W=8,10", "-o", study.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(study / "summary.csv");
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[1].at("warm_start"), "0");
  // The same wind solved alone, from the problem's own guess.
  const RunResult cold = run_lagrange(dir.path(), {"optimize", kRotor, "--set", "W=10"});
  ASSERT_EQ(cold.exit_code, 0) << cold.err;
  const auto field = [&](const std::string& label) {
    const size_t at = cold.out.find(label);
    EXPECT_NE(at, std::string::npos) << cold.out;
    return cold.out.substr(at + label.size());
  };
  const double objective = std::stod(field("objective"));
  const int iterations = std::stoi(field("optimal solution found ("));
  EXPECT_NEAR(std::stod(rows[1].at("objective")), objective, 1e-6 * objective);
  EXPECT_LT(std::stoi(rows[1].at("iterations")), iterations);
}

TEST(OptimalSweep, PlotsTheCurveOfTheCasesThatSucceeded) {
  if (!plot_format_available(PlotFormat::Svg)) GTEST_SKIP() << "gnuplot with svg is not installed";
  ScratchDir dir("optimal_plot");
  const fs::path study = dir.path() / "curve", svg = dir.path() / "curve.svg";
  const RunResult r =
      run_lagrange(dir.path(), {"sweep", kRotor, "--optimize", "--vary", "W=0.5,4,8", "--plot",
                                svg.string(), "-o", study.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = slurp(svg);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("objective"), std::string::npos);
  EXPECT_FALSE(fs::exists(svg.string() + ".part"));
}

TEST(OptimalSweep, MistakesAreRefusedBeforeAnythingRuns) {
  ScratchDir dir("optimal_refused");
  const std::string pendulum = std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml";
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"sweep", pendulum, "--optimize", "--vary", "l2=1,2"}, "no optimal_control section"},
      {{"sweep", kRotor, "--optimize", "--vary", "W=4,8", "--t-end", "3"}, "--t-end"},
      {{"sweep", kRotor, "--vary", "W=4,8", "--intervals", "5"}, "apply to --optimize"},
      {{"sweep", kRotor, "--optimize", "--vary", "W=4,8", "--metric", "objective=max(u)"},
       "named like a column"},
      {{"sweep", kRotor, "--optimize", "--vary", "W=4,8", "--vary", "k=1,2", "--plot", "a.svg"},
       "one --vary"}};
  for (const auto& [args, fragment] : bad) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", (dir.path() / "st").string()});
    const RunResult r = run_lagrange(dir.path(), a);
    EXPECT_EQ(r.exit_code, 2) << fragment << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "st" / "summary.csv")) << fragment;
  }
}

}  // namespace
}  // namespace lagrange::cli
