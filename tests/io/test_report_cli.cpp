// `lagrange simulate --report` and `lagrange report` as a user meets them: the file written, and
// the mistakes (wrong extension, a CSV of another model, a bad visual section) with their exit
// codes and messages.

#include <gtest/gtest.h>

#include "hardening/cli_runner.hpp"
#include "support/harness.hpp"

namespace lagrange::hardening {
namespace {

// The report holds its data and the whole front-end: nothing is loaded from elsewhere.
void expect_self_contained_report(const fs::path& html, const std::string& name) {
  const std::string text = slurp(html);
  EXPECT_EQ(text.rfind("<!doctype html>", 0), 0u);
  EXPECT_NE(text.find("<title>" + name + " — lagrange report</title>"), std::string::npos);
  EXPECT_NE(text.find("id=\"lagrange-data\""), std::string::npos);
  EXPECT_EQ(text.find("<script src"), std::string::npos);
  EXPECT_EQ(text.find("<link "), std::string::npos);
  EXPECT_EQ(text.find("@import"), std::string::npos);
}

TEST(ReportCli, SimulateWritesTheReportBesideTheCsv) {
  ScratchDir dir("report-simulate");
  const auto html = dir.path() / "out" / "pendulum.html";
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", testing::example_path("pendulum.yaml"), "--t-end", "1",
                                "-o", (dir.path() / "p.csv").string(), "--report", html.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + html.string()), std::string::npos) << r.out;
  expect_self_contained_report(html, "pendulum");
}

TEST(ReportCli, ReportOfASavedTrajectory) {
  ScratchDir dir("report-saved");
  const auto csv = dir.path() / "brick.csv", html = dir.path() / "brick.html";
  ASSERT_EQ(run_lagrange(dir.path(), {"simulate", testing::example_path("tumbling_brick.yaml"),
                                      "--t-end", "0.5", "-q", "-o", csv.string()})
                .exit_code,
            0);
  const RunResult r = run_lagrange(
      dir.path(),
      {"report", testing::example_path("tumbling_brick.yaml"), csv.string(), "-o", html.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + html.string() + " (51 samples of tumbling brick)"),
            std::string::npos)
      << r.out;
  expect_self_contained_report(html, "tumbling brick");
}

TEST(ReportCli, ACsvOfAnotherModelIsAUsageError) {
  ScratchDir dir("report-other");
  const auto csv = dir.path() / "p.csv", html = dir.path() / "x.html";
  ASSERT_EQ(run_lagrange(dir.path(), {"simulate", testing::example_path("pendulum.yaml"), "--t-end",
                                      "0.2", "-q", "-o", csv.string()})
                .exit_code,
            0);
  const RunResult r = run_lagrange(
      dir.path(),
      {"report", testing::example_path("double_pendulum.yaml"), csv.string(), "-o", html.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the trajectory has no column 'theta1' of the model"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(html));
  const RunResult missing = run_lagrange(
      dir.path(),
      {"report", testing::example_path("pendulum.yaml"), "nope.csv", "-o", html.string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("cannot open the trajectory 'nope.csv'"), std::string::npos)
      << missing.err;
}

TEST(ReportCli, AReportNotEndingInHtmlIsRefusedBeforeTheRun) {
  ScratchDir dir("report-ext");
  const auto csv = dir.path() / "p.csv";
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", testing::example_path("pendulum.yaml"), "-o",
                                csv.string(), "--report", (dir.path() / "r.txt").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("expected a file name ending in .html"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(csv)) << "nothing is written";
}

TEST(ReportCli, AVisualMistakeIsAModelErrorBeforeTheRun) {
  ScratchDir dir("report-visual");
  const auto model = dir.path() / "m.yaml", csv = dir.path() / "m.csv";
  spit(model,
       "coordinates: {x: {initial: 1}}\npoints: {p: [x, 0, 0]}\nparticles: {p: 1}\n"
       "kinetic: 0\npotential: x^2/2\nvisual:\n  trail: [q]\n");
  const RunResult r = run_lagrange(dir.path(), {"simulate", model.string(), "-o", csv.string(),
                                                "--report", (dir.path() / "m.html").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(
      r.err.find("m.yaml:7:11: error: expected a point, body or element name in visual, got 'q'"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(csv));
}

}  // namespace
}  // namespace lagrange::hardening
