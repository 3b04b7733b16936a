// `--integrator` as a user meets it: a named ARKODE table runs; a misspelt name exits 2 before any
// work, listing the valid names; the same name in a model file is a model error at its position.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli/shell_run.hpp"

namespace {

namespace fs = std::filesystem;

using Result = lagrange::testing::ShellResult;

Result run(const std::string& args) {
  return lagrange::testing::run_shell(args);
}

const std::string kPendulum = std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml";

TEST(IntegratorOption, ANamedTableRunsAndIsReported) {
  const Result r = run("simulate " + kPendulum + " --t-end 1 --integrator arkode:verner65");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("arkode:verner65"), std::string::npos) << r.output;
}

TEST(IntegratorOption, AnUnknownNameExitsTwoListingTheValidOnes) {
  const fs::path csv = fs::temp_directory_path() / "lagrange_integrator_option.csv";
  fs::remove(csv);
  const Result r =
      run("simulate " + kPendulum + " --integrator arkode:verner56 -o " + csv.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("arkode:verner56"), std::string::npos) << r.output;
  for (const char* name : {"arkode:dormand-prince", "arkode:verner65", "cvode", "midpoint"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name << " not listed in " << r.output;
  EXPECT_FALSE(fs::exists(csv));
}

TEST(IntegratorOption, AnUnknownNameInTheModelFileIsAModelError) {
  const fs::path model = fs::temp_directory_path() / "lagrange_integrator_option.yaml";
  std::ofstream(model) << "name: p\nparameters: {g: 9.81}\ncoordinates:\n  x: {initial: 1}\n"
                          "kinetic: der(x)^2/2\npotential: g*x^2/2\n"
                          "simulate: {integrator: arkode:rk45}\n";
  const Result r = run("simulate " + model.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(":7:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown integrator 'arkode:rk45'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("arkode:verner65"), std::string::npos) << r.output;
}

}  // namespace
