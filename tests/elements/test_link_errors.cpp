// `links:` and `derive --form manipulator` through the command line (bad link input is in
// test_element_errors.cpp).

#include <gtest/gtest.h>

#include <string>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// `derive --form manipulator` on the seed's elbow manipulator, and a clear refusal for a
// constrained model.
TEST(LinksCli, DeriveManipulatorForm) {
  ScratchDir dir("links-derive");
  const std::string examples = std::string(LAGRANGE_SOURCE_DIR) + "/examples/";
  RunResult r = run_lagrange(
      dir.path(), {"derive", examples + "elbow_manipulator.yaml", "--form", "manipulator"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // GiNaC orders factors by hash, which may differ between runs: look at the line's pieces.
  const size_t c121 = r.out.find("  c_{121} = -");
  ASSERT_NE(c121, std::string::npos) << r.out;
  const std::string line = r.out.substr(c121, r.out.find('\n', c121) - c121);
  for (const char* factor : {"Lc2", "m2", "L1", "sin(q2)"})
    EXPECT_NE(line.find(factor), std::string::npos) << line;
  EXPECT_EQ(r.out.find("c_{111}"), std::string::npos) << r.out;
  // The link Jacobians: the forearm turns with q1 + q2 about z.
  EXPECT_NE(r.out.find("  J_w(fore) = [[0, 0], [0, 0], [1, 1]]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  J_v(upper) = [["), std::string::npos) << r.out;
  r = run_lagrange(dir.path(), {"derive", examples + "elbow_manipulator.yaml", "--form",
                                "manipulator", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"christoffel\""), std::string::npos);
  EXPECT_NE(r.out.find("\"jacobians\""), std::string::npos);
  r = run_lagrange(dir.path(), {"derive", examples + "five_bar.yaml", "--form", "manipulator"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("the manipulator form needs an unconstrained model, got 2 constraints"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
