// `--integrator` as a user meets it: a named ARKODE table runs; a misspelt name exits 2 before any
// work, listing the valid names; the same name in a model file is a model error at its position.
// `--max-order` (and `simulate: max_order`) reaches the BDF methods.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "cli/shell_run.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

using Result = lagrange::testing::ShellResult;
using lagrange::testing::run_shell;

const std::string kPendulum = std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml";

TEST(IntegratorOption, ANamedTableRunsAndIsReported) {
  const Result r = run_shell("simulate " + kPendulum + " --t-end 1 --integrator arkode:verner65");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("arkode:verner65"), std::string::npos) << r.output;
}

TEST(IntegratorOption, AnUnknownNameExitsTwoListingTheValidOnes) {
  const lagrange::test::ScratchDir dir("unknown-integrator");
  const fs::path csv = dir.path() / "run.csv";
  const Result r =
      run_shell("simulate " + kPendulum + " --integrator arkode:verner56 -o " + csv.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("arkode:verner56"), std::string::npos) << r.output;
  for (const char* name : {"arkode:dormand-prince", "arkode:verner65", "cvode", "midpoint"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name << " not listed in " << r.output;
  EXPECT_FALSE(fs::exists(csv));
}

TEST(IntegratorOption, AnUnknownNameInTheModelFileIsAModelError) {
  const lagrange::test::ScratchDir dir("integrator-in-model");
  const fs::path model = dir.path() / "model.yaml";
  std::ofstream(model) << "name: p\nparameters: {g: 9.81}\ncoordinates:\n  x: {initial: 1}\n"
                          "kinetic: der(x)^2/2\npotential: g*x^2/2\n"
                          "simulate: {integrator: arkode:rk45}\n";
  const Result r = run_shell("simulate " + model.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(":7:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown integrator 'arkode:rk45'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("arkode:verner65"), std::string::npos) << r.output;
}

// The last value of column `name` in a CSV written by `simulate`.
double last_value(const fs::path& csv, const std::string& name) {
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  size_t column = 0;
  for (size_t at = 0, next; (next = header.find(',', at)) != std::string::npos; at = next + 1) {
    if (header.substr(at, next - at) == name) break;
    ++column;
  }
  std::stringstream row(last);
  std::string cell;
  for (size_t i = 0; i <= column; ++i) std::getline(row, cell, ',');
  return std::stod(cell);
}

// An undamped oscillator on CVODE at a loose tolerance: at order 1 (backward Euler, which damps
// every oscillation numerically) it loses far more energy than at BDF's default orders up to 5;
// the flag and the model file's key give the same run bit for bit; 6 is refused before any work.
TEST(IntegratorOption, MaxOrderReachesTheBdfMethods) {
  const lagrange::test::ScratchDir folder("max-order");
  const fs::path& dir = folder.path();
  const std::string base =
      "name: osc\nparameters: {g: 9.81}\ncoordinates:\n  x: {initial: 1}\n"
      "kinetic: der(x)^2/2\npotential: g*x^2/2\n";
  std::ofstream(dir / "osc.yaml")
      << base << "simulate: {t_end: 10, integrator: cvode, rtol: 1e-4, atol: 1e-8}\n";
  std::ofstream(dir / "osc_order1.yaml")
      << base << "simulate: {t_end: 10, integrator: cvode, rtol: 1e-4, atol: 1e-8, max_order: 1}\n";
  const auto simulate = [&](const std::string& model, const std::string& extra,
                            const std::string& csv) {
    const Result r =
        run_shell("simulate " + (dir / model).string() + " -q -o " + (dir / csv).string() + extra);
    EXPECT_EQ(r.code, 0) << r.output;
  };
  simulate("osc.yaml", "", "default.csv");
  simulate("osc.yaml", " --max-order 1", "flag.csv");
  simulate("osc_order1.yaml", "", "key.csv");
  const auto slurp = [&](const char* csv) {
    std::ifstream in(dir / csv);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(slurp("flag.csv"), slurp("key.csv"));
  const double e0 = 9.81 / 2, lost1 = e0 - last_value(dir / "flag.csv", "energy"),
               lost5 = e0 - last_value(dir / "default.csv", "energy");
  EXPECT_GT(lost1, 0.05 * e0) << "backward Euler's numerical damping";
  EXPECT_LT(std::abs(lost5), 0.2 * lost1);

  const Result bad = run_shell("simulate " + (dir / "osc.yaml").string() + " --max-order 6 -o " +
                               (dir / "bad.csv").string());
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--max-order must be from 1 to 5"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "bad.csv"));
  fs::remove_all(dir);
}

}  // namespace
