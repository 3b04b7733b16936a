// `lagrange --version`, as a user meets it: the version and the git revision of the build on
// stdout, exit 0, whatever else is on the command line.

#include <gtest/gtest.h>

#include <regex>

#include "hardening/cli_runner.hpp"

namespace {

using lagrange::hardening::run_lagrange;
using lagrange::hardening::ScratchDir;

TEST(CliVersion, PrintsVersionAndRevision) {
  ScratchDir dir("version");
  const auto r = run_lagrange(dir.path(), {"--version"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // "lagrange 0.1.0 (git 5a215df)", "(git 5a215df-dirty)", or "(git unknown)" outside a checkout
  EXPECT_TRUE(
      std::regex_match(r.out, std::regex(R"(lagrange \d+\.\d+\.\d+ \(git [0-9a-z.-]+\)\n)")))
      << "got '" << r.out << "'";
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

TEST(CliVersion, NamedInHelp) {
  ScratchDir dir("version-help");
  const auto r = run_lagrange(dir.path(), {"--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--version"), std::string::npos) << r.out;
}

TEST(CliVersion, WithASubcommandStillPrintsTheVersion) {
  ScratchDir dir("version-sub");
  const auto r = run_lagrange(dir.path(), {"--version", "check", "no-such-model.yaml"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("lagrange ", 0), 0u) << r.out;
}

}  // namespace
