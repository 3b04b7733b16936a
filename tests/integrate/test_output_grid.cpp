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

TEST(OutputGrid, RejectsBadInput) {
  EXPECT_THROW(OutputGrid(0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(OutputGrid(0.0, 1.0, -0.1), std::invalid_argument);
  EXPECT_THROW(OutputGrid(1.0, 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(OutputGrid(0.0, std::nan(""), 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange::integration
