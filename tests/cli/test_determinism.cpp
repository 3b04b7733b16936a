// Determinism across processes (issue 8, item 10): every example, run twice as separate
// `lagrange` processes with address-space randomisation as the system has it (no re-exec),
// exports byte-identical C (the tape, instruction for instruction) and writes byte-identical
// trajectories. GiNaC's own term order changes with load addresses, so this fails when a tape
// is built in GiNaC's order.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

std::vector<std::string> example_names() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(fs::path(LAGRANGE_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// The files `lagrange export --c` and `lagrange simulate -o` (CSV and sidecar) write for
/// `name`, one process each, as (file name, content) pairs.
std::vector<std::pair<std::string, std::string>> outputs_of(const std::string& name,
                                                            const fs::path& dir) {
  const std::string model =
      (fs::path(LAGRANGE_SOURCE_DIR) / "examples" / (name + ".yaml")).string();
  const fs::path c_dir = dir / "c", csv = dir / "run.csv";
  const RunResult exported = run_lagrange(dir, {"export", model, "--c", c_dir.string()});
  EXPECT_EQ(exported.exit_code, 0) << exported.err;
  const RunResult simulated =
      run_lagrange(dir, {"simulate", model, "-q", "--t-end", "1", "-o", csv.string()});
  EXPECT_EQ(simulated.exit_code, 0) << simulated.err;
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& e : fs::directory_iterator(c_dir))
    files.emplace_back(e.path().filename().string(), slurp(e.path()));
  files.emplace_back("run.csv", slurp(csv));
  files.emplace_back("run.csv.json", slurp(dir / "run.csv.json"));
  std::sort(files.begin(), files.end());
  return files;
}

class AcrossProcesses : public ::testing::TestWithParam<std::string> {};

TEST_P(AcrossProcesses, SameTapeAndTrajectory) {
  ScratchDir first("det-1-" + GetParam()), second("det-2-" + GetParam());
  const auto a = outputs_of(GetParam(), first.path());
  const auto b = outputs_of(GetParam(), second.path());
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 4u);  // lagrange_model.c, lagrange_model.h, run.csv, run.csv.json
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].first, b[i].first);
    EXPECT_FALSE(a[i].second.empty()) << a[i].first;
    EXPECT_TRUE(a[i].second == b[i].second) << a[i].first << " differs between two processes";
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, AcrossProcesses, ::testing::ValuesIn(example_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace lagrange::hardening
