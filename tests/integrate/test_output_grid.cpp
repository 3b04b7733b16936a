// The uniform output grid: t0 + k·dt, last sample exactly t_end.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "integrate/output_grid.hpp"

namespace lagrange::integration {
namespace {

TEST(OutputGrid, IntegerRatioEndsExactlyAtTEnd) {
  const OutputGrid grid(0.0, 10.0, 0.1);  // 10 / 0.1 is 100 only up to rounding
  ASSERT_EQ(grid.intervals(), 100u);
  for (size_t k = 0; k < 100; ++k) EXPECT_EQ(grid.time(k), 0.0 + static_cast<double>(k) * 0.1);
  EXPECT_EQ(grid.time(100), 10.0);
}

TEST(OutputGrid, NonIntegerRatioAddsAShortLastInterval) {
  const OutputGrid grid(1.0, 2.0, 0.3);
  ASSERT_EQ(grid.intervals(), 4u);
  EXPECT_EQ(grid.time(0), 1.0);
  EXPECT_EQ(grid.time(3), 1.0 + 3 * 0.3);
  EXPECT_EQ(grid.time(4), 2.0);
}

TEST(OutputGrid, RatioWithinOneBillionthCountsAsInteger) {
  const OutputGrid grid(0.0, 1.0 + 1e-12, 0.25);
  EXPECT_EQ(grid.intervals(), 4u);
  EXPECT_EQ(grid.time(4), 1.0 + 1e-12);
}

TEST(OutputGrid, EmptySpanHasOnlyTheInitialSample) {
  const OutputGrid grid(3.0, 3.0, 0.5);
  EXPECT_EQ(grid.intervals(), 0u);
  EXPECT_EQ(grid.time(0), 3.0);
}

// A handover mid-run (auto turning implicit) continues on the same sample times, bit for bit.
TEST(OutputGrid, TailKeepsTheSampleTimes) {
  const OutputGrid grid(0.0, 2.0, 0.3);
  const OutputGrid tail = grid.from(3);
  ASSERT_EQ(tail.intervals(), grid.intervals() - 3);
  for (size_t k = 0; k <= tail.intervals(); ++k) EXPECT_EQ(tail.time(k), grid.time(k + 3));
  EXPECT_EQ(grid.from(2).from(1).time(0), grid.time(3));
  EXPECT_EQ(grid.from(grid.intervals()).intervals(), 0u);
  EXPECT_THROW(grid.from(grid.intervals() + 1), std::out_of_range);
}

TEST(OutputGrid, RejectsBadInput) {
  EXPECT_THROW(OutputGrid(0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(OutputGrid(0.0, 1.0, -0.1), std::invalid_argument);
  EXPECT_THROW(OutputGrid(1.0, 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(OutputGrid(0.0, std::nan(""), 0.1), std::invalid_argument);
  // More intervals than a run may keep (kMaxOutputIntervals): once cast to size_t past its range.
  EXPECT_THROW(OutputGrid(0.0, 10.0, 1e-100), std::invalid_argument);
  EXPECT_THROW(OutputGrid(0.0, 1e300, 1e-300), std::invalid_argument);
  EXPECT_EQ(OutputGrid(0.0, 1.0, 1e-8).intervals(), 100000000u);  // the bound itself
}

}  // namespace
}  // namespace lagrange::integration
