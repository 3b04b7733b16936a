// Determinism across processes (issue 8, item 10): every example, run twice as separate
// `lagrange` processes with address-space randomisation as the system has it (no re-exec),
// exports byte-identical C (the tape, instruction for instruction) and writes byte-identical
// trajectories. GiNaC's own term order changes with load addresses, so this fails when a tape
// is built in GiNaC's order.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "support/test_paths.hpp"
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

// Initial values and rates written as expressions of parameters are evaluated in the tape's
// order, not by GiNaC's evalf, which adds floating-point terms in its own order.
TEST(AcrossProcesses, InitialStateFromParameterExpressions) {
  ScratchDir dir("det-initial");
  const fs::path model = dir.path() / "model.yaml";
  spit(model,
       "name: initial state from parameters\n"
       "parameters: {a: 0.1, b: 0.2, c: 0.3, d: 1e-17, e: 0.7, f: 3.3e-5, l: 1.0, g: 9.81}\n"
       "coordinates:\n"
       "  th: {initial: a + b + c + d + e + f - 1.3, rate: a*b + c*e + d - b*c + f*a}\n"
       "  ph: {initial: e - a - b - c - d + f, rate: a + c + e - b - d - f}\n"
       "points:\n"
       "  p: [l*sin(th), -l*cos(th), 0]\n"
       "  q: p + [l*sin(ph), -l*cos(ph), 0]\n"
       "particles: {p: 1.0, q: 1.0}\n"
       "gravity: [0, -g, 0]\n"
       "simulate: {t_end: 0.5, output_step: 0.1}\n");
  std::string first;
  for (int run = 0; run < 4; ++run) {
    const fs::path csv = dir.path() / ("run" + std::to_string(run) + ".csv");
    const RunResult r =
        run_lagrange(dir.path(), {"simulate", model.string(), "-q", "-o", csv.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string bytes = slurp(csv);
    ASSERT_FALSE(bytes.empty());
    if (run == 0) first = bytes;
    EXPECT_TRUE(bytes == first) << "run " << run << " differs from run 0";
  }
}

}  // namespace
}  // namespace lagrange::hardening
