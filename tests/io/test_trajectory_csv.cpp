// The CSV contract: header, column order, 17 significant digits, status sidecar.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lagrange/io.hpp"
#include "support/harness.hpp"
#include "support/scratch_dir.hpp"

namespace lagrange {
namespace {

TEST(TrajectoryCsv, HeaderOrderAndRoundTrip) {
  auto sys = testing::load_example("cartesian_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 0.5;
  const Trajectory tr = sys.run(so);
  const test::ScratchDir dir("trajectory-csv");
  const auto path = (dir.path() / "run.csv").string();
  write_trajectory_csv(tr, path);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "t,x,y,x_dot,y_dot,kinetic,potential,energy,rod,constraint_residual,"
            "constraint_rate_residual");
  std::string line;
  size_t rows = 0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    for (size_t c = 0; std::getline(ss, cell, ','); ++c)
      EXPECT_EQ(std::stod(cell), tr.data[rows * tr.columns.size() + c]) << "exact round trip";
    ++rows;
  }
  EXPECT_EQ(rows, tr.rows());
  const auto side = nlohmann::json::parse(std::ifstream(path + ".json"));
  EXPECT_EQ(side["status"], "complete");
  EXPECT_EQ(side["rows"], tr.rows());
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
}

}  // namespace
}  // namespace lagrange
