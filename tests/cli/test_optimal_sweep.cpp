// An optimisation study's order and starts (src/cli/optimal_sweep.cpp, docs/sweeps.md "Optimal
// control: a power curve"): the cases run outwards from the model file's own values, each
// started from the nearest solved case.

#include <gtest/gtest.h>

#include <vector>

#include "cli/optimal_sweep.hpp"

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

}  // namespace
}  // namespace lagrange::cli
