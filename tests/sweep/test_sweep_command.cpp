// `lagrange sweep` as a user meets it (issue 24): each case is, bit for bit, the run that
// `simulate --set` makes alone, with one worker and with two; failing cases are recorded and the
// others finish; a study stopped by SIGINT resumes to the same summary; bad input is refused
// before anything runs or is written.

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/test_paths.hpp"

namespace lagrange::hardening {
namespace {

const std::string kModel = std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml";

using Row = std::map<std::string, std::string>;

std::vector<Row> read_summary(const fs::path& path) {
  std::istringstream in(slurp(path));
  std::string line, field;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, field, ',');) header.push_back(field);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row row;
    std::istringstream r(line);
    for (const auto& name : header) {
      std::getline(r, field, ',');
      row[name] = field;
    }
    rows.push_back(row);
  }
  return rows;
}

// A summary's text without its wall-time column, the one field that differs between runs.
std::string without_wall_time_of(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

std::string without_wall_time(const fs::path& path) {
  return without_wall_time_of(slurp(path));
}

const std::vector<std::string> kStudy{"--vary",   "l2=0.5:1.5:3",
                                      "--vary",   "m2=1,2.5",
                                      "--metric", "final(theta1)",
                                      "--metric", "peak=max(abs(theta2), t > 1)",
                                      "--t-end",  "2",
                                      "-q"};

std::vector<std::string> study_args(const fs::path& dir, std::vector<std::string> extra) {
  std::vector<std::string> args{"sweep", kModel, "-o", dir.string()};
  args.insert(args.end(), kStudy.begin(), kStudy.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Every case's trajectory equals, byte for byte, `simulate --set` of its values alone, with one
// worker and with two; so do the metrics computed from it. Each lone run is made once, for the
// first study, and compared with both.
TEST(SweepCommand, CasesAreBitIdenticalToSimulateSet) {
  ScratchDir dir("sweep-identical");
  std::map<std::string, std::string> lone;  // case and values -> `simulate --set`'s CSV
  for (const char* jobs : {"1", "2"}) {
    const fs::path study = dir.path() / (std::string("j") + jobs);
    const RunResult r =
        run_lagrange(dir.path(), study_args(study, {"-j", jobs, "--keep-trajectories"}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<Row> rows = read_summary(study / "summary.csv");
    ASSERT_EQ(rows.size(), 6u);
    for (const Row& row : rows) {
      EXPECT_EQ(row.at("status"), "ok");
      const std::string key = row.at("case") + ":" + row.at("l2") + "," + row.at("m2");
      if (!lone.count(key)) {
        const fs::path alone = dir.path() / ("alone_" + row.at("case") + ".csv");
        const RunResult s = run_lagrange(
            dir.path(), {"simulate", kModel, "--set", "l2=" + row.at("l2"), "--set",
                         "m2=" + row.at("m2"), "--t-end", "2", "-o", alone.string(), "-q"});
        ASSERT_EQ(s.exit_code, 0) << s.err;
        lone[key] = slurp(alone);
      }
      const std::string& expected = lone.at(key);
      EXPECT_EQ(slurp(study / ("case_" + row.at("case") + ".csv")), expected)
          << "case " << row.at("case") << " with -j" << jobs;
      // The metrics from the lone run's CSV: the last theta1, the largest |theta2| after t = 1.
      std::istringstream csv(expected);
      std::string line, field;
      std::getline(csv, line);
      double last = NAN, peak = -1;
      while (std::getline(csv, line)) {
        std::vector<double> v;
        for (std::istringstream f(line); std::getline(f, field, ',');)
          v.push_back(std::stod(field));
        last = v[1];
        if (v[0] > 1) peak = std::max(peak, std::abs(v[2]));
      }
      EXPECT_EQ(std::stod(row.at("final(theta1)")), last);
      // The peak is located between samples (docs/theory.md §9.2; exact in test_study_cases):
      // at least the largest sample, and near it at this output step.
      EXPECT_GE(std::stod(row.at("peak")), peak);
      EXPECT_NEAR(std::stod(row.at("peak")), peak, 1e-2 * peak);
    }
  }
  EXPECT_EQ(without_wall_time(dir.path() / "j1" / "summary.csv"),
            without_wall_time(dir.path() / "j2" / "summary.csv"));
}

// The kite varying its wind, a chain varying its damping (their inputs from one traced read of
// the model file) and the chain varying its length (its shape: a read per case): a case is, bit
// for bit, `simulate --set` of its values alone.
TEST(SweepCommand, KiteAndTetherCasesAreBitIdenticalToSimulateSet) {
  struct Study {
    const char* model;
    std::string name, a, b;  ///< the parameter and its two values
    const char* inputs;      ///< where the summary line says the inputs came from
  };
  ScratchDir dir("sweep-kite-tether");
  for (const Study& st : {Study{"figure_eight.yaml", "W", "6", "9.5", "from one read"},
                          Study{"hanging_chain.yaml", "c", "1", "3.5", "from one read"},
                          Study{"hanging_chain.yaml", "L", "10", "10.5", "reading the cases'"}}) {
    const std::string model = std::string(LAGRANGE_SOURCE_DIR) + "/examples/" + st.model;
    const fs::path study = dir.path() / ("study_" + st.name);
    const RunResult r = run_lagrange(
        dir.path(), {"sweep", model, "--vary", st.name + "=" + st.a + "," + st.b, "--t-end", "0.5",
                     "-o", study.string(), "-j", "2", "--keep-trajectories"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(st.inputs), std::string::npos) << r.out;
    // Case 1: the one whose inputs are not those of the traced read's values (case 0's).
    const fs::path alone = dir.path() / ("alone_" + st.name + ".csv");
    const RunResult s = run_lagrange(dir.path(), {"simulate", model, "--set", st.name + "=" + st.b,
                                                  "--t-end", "0.5", "-o", alone.string(), "-q"});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    EXPECT_EQ(slurp(study / "case_1.csv"), slurp(alone)) << st.model << " " << st.name;
    EXPECT_TRUE(fs::exists(study / "case_0.csv"));
  }
}

// A massless second bob makes M singular: those cases fail with the reason, the rest finish.
TEST(SweepCommand, FailingCasesAreRecordedAndTheRestFinish) {
  ScratchDir dir("sweep-failures");
  const RunResult r =
      run_lagrange(dir.path(), {"sweep", kModel, "--vary", "m2=1,0,2", "--metric", "final(theta2)",
                                "--metric", "drift(energy)", "--t-end", "1", "-o",
                                (dir.path() / "study").string(), "-j", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(dir.path() / "study" / "summary.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[1].at("status"), "failed");
  EXPECT_FALSE(rows[1].at("reason").empty());
  EXPECT_EQ(rows[2].at("status"), "ok");
  EXPECT_TRUE(std::isfinite(std::stod(rows[2].at("final(theta2)"))));
  // The pendulum conserves energy (about 30 J here): at rtol 1e-10 it drifts by far less.
  for (const size_t ok : {0, 2}) EXPECT_LT(std::stod(rows[ok].at("drift(energy)")), 1e-6);
}

// Metrics in the model file, of several columns and of the parameters, beside --metric ones:
// max(x2 / (l1 + l2)) times l1 + l2 of each case is that case's max(x2), so the parameters a
// metric reads are the case's own; a bad one is refused at its line before anything is written.
TEST(SweepCommand, ModelFileMetricsReadTheCaseParameters) {
  ScratchDir dir("sweep-model-metrics");
  const std::string model = (dir.path() / "metrics.yaml").string();
  spit(model, slurp(kModel) + "metrics:\n  reach: max(x2 / (l1 + l2))\n  swing: final(theta1)\n");
  const fs::path study = dir.path() / "study";
  const RunResult r = run_lagrange(
      dir.path(), {"sweep", model, "--vary", "l2=0.5,1,2", "--metric", "max(x2)", "--metric",
                   "final(theta1)", "--t-end", "2", "-o", study.string(), "-j", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(study / "summary.csv");
  ASSERT_EQ(rows.size(), 3u);
  for (const Row& row : rows) {
    ASSERT_EQ(row.at("status"), "ok");
    const double l2 = std::stod(row.at("l2")), reach = std::stod(row.at("reach"));
    EXPECT_NEAR(reach * (1.0 + l2), std::stod(row.at("max(x2)")), 1e-12 * (1.0 + l2)) << l2;
    EXPECT_EQ(row.at("swing"), row.at("final(theta1)"));
  }

  // `simulate` prints the model file's metrics with its summary: swing is the final theta1.
  const RunResult sim = run_lagrange(
      dir.path(), {"simulate", model, "--t-end", "2", "-o", (dir.path() / "run.csv").string()});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_NE(sim.out.find("  metrics: reach = "), std::string::npos) << sim.out;
  const std::string final_line = sim.out.substr(sim.out.find("final state: theta1 = ") + 22);
  const double theta1 = std::stod(final_line),
               swing = std::stod(sim.out.substr(sim.out.find("swing = ") + 8));
  EXPECT_NEAR(swing, theta1, 1e-5 * std::abs(theta1));  // printed with 6 and 10 digits

  spit(model, slurp(kModel) + "metrics:\n  bad: max(theta3)\n");
  fs::remove_all(study);
  const RunResult bad = run_lagrange(
      dir.path(), {"sweep", model, "--vary", "l2=1,2", "--t-end", "1", "-o", study.string()});
  EXPECT_NE(bad.exit_code, 0);
  const std::string base = slurp(kModel);  // `bad:` is on the second line after it
  const auto line = std::count(base.begin(), base.end(), '\n') + 2;
  EXPECT_NE(bad.err.find("metrics.yaml:" + std::to_string(line) + ":"), std::string::npos)
      << bad.err;
  EXPECT_NE(bad.err.find("unknown name 'theta3'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(study / "summary.csv"));
}

// The rows a study's summary holds now (0 before it is published).
size_t rows_in(const fs::path& study) {
  std::error_code ec;
  return fs::exists(study / "summary.csv", ec) ? read_summary(study / "summary.csv").size() : 0u;
}

// Waits, up to 10 s, until a running study's summary holds `rows` rows.
void wait_for_rows(const fs::path& study, size_t rows) {
  for (int i = 0; i < 2000 && rows_in(study) < rows; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

// SIGINT part-way (to the study's process alone, with two worker processes, which it passes the
// signal on to): exit 130 with the finished cases kept; --resume runs only the others and the
// summary equals that of a study never stopped, each case once.
TEST(SweepCommand, InterruptedStudyResumesToTheSameSummary) {
  ScratchDir dir("sweep-resume");
  const std::vector<std::string> grid{
      "--vary", "l2=0.5:1.5:30", "--metric", "final(theta1)", "--t-end", "30", "-q"};
  const auto args = [&](const fs::path& study, bool resume, const char* jobs = "1") {
    std::vector<std::string> a{"sweep", kModel, "-o", study.string(), "-j", jobs};
    a.insert(a.end(), grid.begin(), grid.end());
    if (resume) a.push_back("--resume");
    return a;
  };
  const fs::path whole = dir.path() / "whole", stopped = dir.path() / "stopped";
  ASSERT_EQ(run_lagrange(dir.path(), args(whole, false)).exit_code, 0);
  Child child(dir.path(), args(stopped, false, "2"));
  wait_for_rows(stopped, 3);
  child.signal(SIGINT);
  const RunResult r = child.wait(std::chrono::seconds(60));
  const size_t kept = rows_in(stopped);
  if (r.exit_code == 0) GTEST_SKIP() << "the study finished before the signal";
  ASSERT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
  ASSERT_GE(kept, 3u);
  ASSERT_LT(kept, 30u);
  EXPECT_EQ(run_lagrange(dir.path(), args(stopped, false)).exit_code, 2);  // not over a study
  auto other = args(stopped, true);
  other.insert(other.end(), {"--rtol", "1e-6"});  // another study: refused, nothing changed
  const RunResult refused = run_lagrange(dir.path(), other);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("started with other options"), std::string::npos) << refused.err;
  EXPECT_EQ(read_summary(stopped / "summary.csv").size(), kept);
  const RunResult resumed = run_lagrange(dir.path(), args(stopped, true));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(without_wall_time(stopped / "summary.csv"), without_wall_time(whole / "summary.csv"));
}

// A worker process killed part-way (SIGKILL, as the machine's OOM killer would): the study stops
// with an error naming it and the rows finished are kept (the other worker finishes its case and
// takes no other); --resume runs the others to the summary of a study never stopped.
TEST(SweepCommand, AKilledWorkerProcessLosesNoFinishedCase) {
  ScratchDir dir("sweep-killed-worker");
  const auto args = [&](const fs::path& study, const char* jobs, bool resume) {
    std::vector<std::string> a{"sweep", kModel, "--vary", "l2=0.5:1.5:30", "--t-end", "30", "-q"};
    a.insert(a.end(), {"--metric", "final(theta1)", "-o", study.string(), "-j", jobs});
    if (resume) a.push_back("--resume");
    return a;
  };
  const fs::path whole = dir.path() / "whole", stopped = dir.path() / "stopped";
  ASSERT_EQ(run_lagrange(dir.path(), args(whole, "1", false)).exit_code, 0);
  Child child(dir.path(), args(stopped, "2", false));
  wait_for_rows(stopped, 3);
  const std::string task =
      "/proc/" + std::to_string(child.pid()) + "/task/" + std::to_string(child.pid()) + "/children";
  pid_t worker = 0;
  std::ifstream(task) >> worker;
  if (worker > 0) kill(worker, SIGKILL);
  const RunResult r = child.wait(std::chrono::seconds(60));
  if (worker <= 0 || r.exit_code == 0) GTEST_SKIP() << "the study finished before the kill";
  // Its own exit code, the case it was running and why (issue 37 item 20: once exit 1, as a
  // model error, naming no case).
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("a worker process (pid " + std::to_string(worker) + ") died from signal 9"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("out-of-memory killer"), std::string::npos) << r.err;
  // Mid-case, the message names the case (which then has no row); the kill may also land between
  // two cases (the worker had finished one and not taken the next), and then it says so.
  const std::smatch running = [&] {
    std::smatch m;
    std::regex_search(r.err, m, std::regex("while running case ([0-9]+) \\(l2 = [0-9.]+\\)"));
    return m;
  }();
  ASSERT_TRUE(!running.empty() || r.err.find("between cases") != std::string::npos) << r.err;
  const size_t kept = rows_in(stopped);
  EXPECT_NE(r.err.find(std::to_string(kept) + " of 30 cases are in"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
  EXPECT_LT(kept, 30u);
  if (!running.empty()) {
    EXPECT_EQ(slurp(stopped / "summary.csv").find("\n" + running[1].str() + ","),
              std::string::npos);
  }
  const RunResult resumed = run_lagrange(dir.path(), args(stopped, "2", true));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(without_wall_time(stopped / "summary.csv"), without_wall_time(whole / "summary.csv"));
}

// Whether process `pid` has ended (gone, or a zombie waiting for init to reap it).
bool ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const size_t close = line.rfind(')');
  return close != std::string::npos && line.size() > close + 2 && line[close + 2] == 'Z';
}

// The study's process killed with SIGKILL (issue 37 item 9): its forked worker, in the middle of a
// case that lasts minutes, ends with it (PR_SET_PDEATHSIG) instead of running on under init.
TEST(SweepCommand, KillingTheStudyKillsItsWorkers) {
  ScratchDir dir("sweep-killed-parent");
  Child child(dir.path(),
              {"sweep", kModel, "--vary", "l2=0.5,1.5", "--t-end", "100000", "--output-step", "10",
               "--compile", "off", "-j", "2", "-q", "-o", (dir.path() / "study").string()});
  const std::string task =
      "/proc/" + std::to_string(child.pid()) + "/task/" + std::to_string(child.pid()) + "/children";
  pid_t worker = 0;
  for (int i = 0; i < 6000 && worker <= 0; ++i) {
    std::ifstream(task) >> worker;
    if (worker <= 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_GT(worker, 0) << "no worker process started";
  child.signal(SIGKILL);
  EXPECT_EQ(child.wait(std::chrono::seconds(10)).exit_code, 128 + SIGKILL);
  for (int i = 0; i < 400 && !ended(worker); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const bool survived = !ended(worker);
  if (survived) kill(worker, SIGKILL);
  EXPECT_FALSE(survived) << "worker " << worker << " outlived the study's process";
}

// Two studies in one directory (issue 37 item 2): once both exited 0 and the summary mixed them.
// The second is refused (exit 2) naming the first's process, and leaves the directory to it; a
// study whose study.txt is gone cannot be resumed.
TEST(SweepCommand, TwoStudiesCannotShareADirectory) {
  ScratchDir dir("sweep-shared-dir");
  const fs::path study = dir.path() / "study";
  const auto args = [&](const char* t_end, std::vector<std::string> extra) {
    std::vector<std::string> a{"sweep", kModel, "--vary",      "l2=0.5,1.5", "--t-end",
                               t_end,   "-j",   "1",           "-q",         "--compile",
                               "off",   "-o",   study.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  fs::create_directories(dir.path() / "first");
  Child first(dir.path() / "first", args("100000", {}));
  for (int i = 0; i < 6000 && slurp(study / ".lock").empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(slurp(study / ".lock"), std::to_string(first.pid()) + "\n");
  const RunResult second = run_lagrange(dir.path(), args("1", {}));
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_NE(second.err.find("another study is running in this directory (process " +
                            std::to_string(first.pid()) + ")"),
            std::string::npos)
      << second.err;
  EXPECT_FALSE(fs::exists(study / "summary.csv"));
  first.signal(SIGKILL);
  first.wait();
  // The lock dies with its holder: a study runs there now, and without study.txt its summary
  // cannot be resumed.
  ASSERT_EQ(run_lagrange(dir.path(), args("1", {})).exit_code, 0);
  fs::remove(study / "study.txt");
  const RunResult resumed = run_lagrange(dir.path(), args("1", {"--resume"}));
  EXPECT_EQ(resumed.exit_code, 2) << resumed.err;
  EXPECT_NE(resumed.err.find("has a summary.csv but no study.txt"), std::string::npos)
      << resumed.err;
}

// A summary edited by hand (issue 37 item 2): a row without a case number, a case twice or one
// beyond the study's cases is refused by --resume (exit 2), the summary left as it was.
TEST(SweepCommand, AResumeOfAnEditedSummaryIsRefused) {
  ScratchDir dir("sweep-edited");
  const fs::path study = dir.path() / "study";
  const std::vector<std::string> args{"sweep", kModel, "--vary", "l2=0.5,1.5",  "--t-end",
                                      "0.5",   "-q",   "-o",     study.string()};
  ASSERT_EQ(run_lagrange(dir.path(), args).exit_code, 0);
  const std::string whole = slurp(study / "summary.csv");
  const std::string first_row =
      whole.substr(whole.find('\n') + 1, whole.find('\n', whole.find('\n') + 1) - whole.find('\n'));
  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  for (const auto& [extra, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"total,1,2\n", "row 3 does not start with a case number"},
           {first_row, "row 3 repeats case 0"},
           {"99" + first_row.substr(first_row.find(',')),
            "has a row of case 99, beyond this study's 2 cases"}}) {
    spit(study / "summary.csv", whole + extra);
    const RunResult r = run_lagrange(dir.path(), resume);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(slurp(study / "summary.csv"), whole + extra);
  }
}

// --resume over a study whose model file (its metrics: section here), random draws or grid
// changed since it started: refused (exit 2) naming what differs, the summary left as it was;
// the unchanged study resumes.
TEST(SweepCommand, AResumeOfAChangedStudyIsRefusedNamingTheChange) {
  ScratchDir dir("sweep-changed");
  const std::string model = (dir.path() / "metrics.yaml").string();
  spit(model, slurp(kModel) + "metrics:\n  swing: final(theta1)\n");
  const fs::path study = dir.path() / "study";
  const auto args = [&](std::vector<std::string> extra, const std::string& seed = "7") {
    std::vector<std::string> a{
        "sweep",           model,       "--vary", "l2=0.5,1", "--random",
        "m2=uniform(1,2)", "--samples", "2",      "--seed",   seed,
        "--t-end",         "1",         "-q",     "-o",       study.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(run_lagrange(dir.path(), args({})).exit_code, 0);
  const std::string summary = slurp(study / "summary.csv");
  const auto refused = [&](std::vector<std::string> extra, const std::vector<std::string>& named,
                           const std::string& seed = "7") {
    extra.push_back("--resume");
    const RunResult r = run_lagrange(dir.path(), args(extra, seed));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    for (const auto& fragment : named) EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(slurp(study / "summary.csv"), summary);
  };
  refused({}, {"was: --seed 7", "now: --seed 8"}, "8");
  refused({"--vary", "l1=1,2"}, {"now: --vary l1=1,2"});
  refused({"--metric", "max(theta2)"}, {"now: --metric max(theta2)"});
  spit(model, slurp(kModel) + "metrics:\n  swing: final(theta2)\n");
  refused({}, {"was: model file sha256: ", "now: model file sha256: ", "was: metric swing: ",
               "now: metric swing: "});
  spit(model, slurp(kModel) + "metrics:\n  swing: final(theta1)\n");
  const RunResult same = run_lagrange(dir.path(), args({"--resume"}));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_EQ(without_wall_time(study / "summary.csv"), without_wall_time_of(summary));
}

// Mistakes in the command line: exit 2 with a message naming them, and no study directory.
TEST(SweepCommand, BadInputIsRefusedBeforeAnythingRuns) {
  ScratchDir dir("sweep-bad");
  const fs::path study = dir.path() / "study";
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad{
      {{"--vary", "k=1,2"}, "no parameter 'k'"},
      {{"--vary", "l2=1:2:0"}, "COUNT"},
      {{"--vary", "l2="}, "no values"},
      {{"--random", "m2=normal(1)", "--samples", "3"}, "two numbers"},
      {{"--random", "m2=normal(1,0.1)"}, "--samples"},
      {{"--vary", "l2=1,2", "--metric", "max(theta3)"}, "unknown name 'theta3'"},
      {{"--metric", "max(theta1)"}, "nothing varies"},
  };
  for (const auto& [extra, fragment] : bad) {
    std::vector<std::string> args{"sweep", kModel, "-o", study.string(), "--t-end", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_lagrange(dir.path(), args);
    EXPECT_EQ(r.exit_code, 2) << fragment << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(study)) << fragment;
  }
}

// A parameter that sets a tether's segment count changes the coordinates: one derivation cannot
// cover it. The worker that reads such a case records it as failed, saying why; the cases the
// derivation covers run.
TEST(SweepCommand, ValuesThatChangeTheStructureFailTheirCase) {
  ScratchDir dir("sweep-structure");
  std::string yaml = slurp(std::string(LAGRANGE_SOURCE_DIR) + "/examples/tether_reel_out.yaml");
  yaml.replace(yaml.find("mu: 0.05}"), 9, "mu: 0.05, n: 8}");
  yaml.replace(yaml.find("segments: 8"), 11, "segments: n");
  spit(dir.path() / "segments.yaml", yaml);
  const fs::path study = dir.path() / "study";
  const RunResult r =
      run_lagrange(dir.path(), {"sweep", (dir.path() / "segments.yaml").string(), "--vary", "n=8,4",
                                "--t-end", "0.1", "-q", "-o", study.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Row> rows = read_summary(study / "summary.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[1].at("status"), "failed");
  const std::string summary = slurp(study / "summary.csv");
  EXPECT_NE(summary.find("change the structure"), std::string::npos) << summary;
}

#ifdef LAGRANGE_HAVE_MPI
// `mpirun -n 2 lagrange sweep`: rank 0 hands the cases to rank 1; the summary equals the one
// worker's, case for case (as root, OpenMPI needs --allow-run-as-root).
TEST(SweepCommand, UnderMpirunTheSummaryIsTheSame) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "mpirun is not installed (openmpi-bin)";
  ScratchDir dir("sweep-mpi");
  const fs::path one = dir.path() / "one", mpi = dir.path() / "mpi";
  ASSERT_EQ(run_lagrange(dir.path(), study_args(one, {"-j", "1"})).exit_code, 0);
  std::string command =
      "mpirun -n 2 --oversubscribe --allow-run-as-root " + std::string(LAGRANGE_BINARY);
  for (const auto& a : study_args(mpi, {})) command += " '" + a + "'";
  command += " > " + (dir.path() / "mpi.log").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << slurp(dir.path() / "mpi.log");
  EXPECT_EQ(without_wall_time(mpi / "summary.csv"), without_wall_time(one / "summary.csv"));
}

// The process below `ancestor` whose environment has OMPI_COMM_WORLD_RANK=`rank` (0 if none).
pid_t rank_process(pid_t ancestor, int rank) {
  const std::string wanted = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    // Walk up the parents: the rank is a child (or grandchild) of mpirun.
    bool below = false;
    for (pid_t p = std::stoi(name), depth = 0; p > 1 && depth < 4 && !below; ++depth) {
      // "pid (comm) state ppid …": comm may hold spaces, so read after its closing parenthesis.
      const std::string stat = slurp(fs::path("/proc") / std::to_string(p) / "stat");
      const auto close = stat.rfind(')');
      if (close == std::string::npos) break;
      std::istringstream rest(stat.substr(close + 1));
      std::string state;
      pid_t parent = 0;
      rest >> state >> parent;
      below = parent == ancestor;
      p = parent;
    }
    if (!below) continue;
    std::string env = slurp(entry.path() / "environ");
    std::replace(env.begin(), env.end(), '\0', '\n');
    if (("\n" + env).find("\n" + wanted + "\n") != std::string::npos)
      return static_cast<pid_t>(std::stoi(name));
  }
  return 0;
}

// SIGKILL of the rank running the cases: mpirun ends the job, the rows already written stay
// whole, and --resume (here on one machine) finishes the study to the summary of one never
// stopped, each case once.
TEST(SweepCommand, UnderMpirunAKilledRankLosesNoFinishedCase) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "mpirun is not installed (openmpi-bin)";
  ScratchDir dir("sweep-mpi-kill");
  const fs::path whole = dir.path() / "whole", killed = dir.path() / "killed";
  const auto args = [&](const fs::path& study) {
    return std::vector<std::string>{
        "sweep", kModel, "--vary", "l2=0.5:1.5:40", "--metric", "final(theta1)", "--t-end",
        "100",   "-q",   "-o",     study.string()};
  };
  ASSERT_EQ(run_lagrange(dir.path(), args(whole)).exit_code, 0);
  std::vector<std::string> argv{"mpirun",       "-n", "2", "--oversubscribe", "--allow-run-as-root",
                                LAGRANGE_BINARY};
  for (const auto& a : args(killed)) argv.push_back(a);
  std::vector<char*> cargv;
  for (auto& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  const std::string log = (dir.path() / "mpirun.log").string();
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t mpirun = 0;
  ASSERT_EQ(posix_spawnp(&mpirun, "mpirun", &fa, nullptr, cargv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  const auto rows = [&] {
    std::error_code ec;
    return fs::exists(killed / "summary.csv", ec) ? read_summary(killed / "summary.csv").size()
                                                  : size_t{0};
  };
  for (int i = 0; i < 6000 && rows() < 3; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const pid_t worker = rank_process(mpirun, 1);
  if (worker > 0) kill(worker, SIGKILL);
  int status = 0;
  for (int i = 0; i < 6000 && waitpid(mpirun, &status, WNOHANG) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (waitpid(mpirun, &status, WNOHANG) == 0) {
    kill(mpirun, SIGKILL);
    waitpid(mpirun, &status, 0);
  }
  ASSERT_GT(worker, 0) << "rank 1 not found\n" << slurp(log);
  const size_t kept = rows();
  if (kept == 40) GTEST_SKIP() << "the study finished before rank 1 was killed";
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << slurp(log);
  EXPECT_GE(kept, 3u);
  auto resume = args(killed);
  resume.push_back("--resume");
  const RunResult r = run_lagrange(dir.path(), resume);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without_wall_time(killed / "summary.csv"), without_wall_time(whole / "summary.csv"));
}
#else
// Under mpirun without MPI built in, every rank would run the whole study: refused.
TEST(SweepCommand, MpirunWithoutMpiIsRefused) {
  ScratchDir dir("sweep-mpirun");
  setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
  const RunResult r = run_lagrange(dir.path(), study_args(dir.path() / "study", {}));
  unsetenv("OMPI_COMM_WORLD_SIZE");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("built without MPI"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "study"));
}
#endif

}  // namespace
}  // namespace lagrange::hardening
