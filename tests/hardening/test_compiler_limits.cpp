// A C compiler that never returns (issue 37 item 10): its time limit ends it and the run goes on
// in the interpreter, saying so; Ctrl-C while it runs ends `simulate`, `sweep` and `export --fmu`
// with 130. Either way no compiler process is left behind and no source stays in the cache.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/test_paths.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::example_path;

/// A "compiler" that writes its process id to `pid_file` and then waits forever on a child of
/// its own (so that killing only the compiler would leave the child running).
fs::path hung_compiler(const ScratchDir& dir) {
  const fs::path script = dir.path() / "hung-cc";
  spit(script, "#!/bin/sh\necho $$ > '" + (dir.path() / "cc.pid").string() + ".part'\nmv '" +
                   (dir.path() / "cc.pid").string() + ".part' '" +
                   (dir.path() / "cc.pid").string() + "'\nsleep 600 &\nwait\n");
  ::chmod(script.c_str(), 0700);
  return script;
}

/// Sets the compiler, the cache and the time limit for the children started meanwhile.
class CompilerEnvironment {
 public:
  CompilerEnvironment(const ScratchDir& dir, const fs::path& compiler, const char* timeout) {
    ::setenv("LAGRANGE_CC", compiler.c_str(), 1);
    ::setenv("LAGRANGE_CACHE_DIR", (dir.path() / "cache").c_str(), 1);
    if (timeout != nullptr) ::setenv("LAGRANGE_CC_TIMEOUT", timeout, 1);
  }
  ~CompilerEnvironment() {
    ::unsetenv("LAGRANGE_CC");
    ::unsetenv("LAGRANGE_CACHE_DIR");
    ::unsetenv("LAGRANGE_CC_TIMEOUT");
  }
  CompilerEnvironment(const CompilerEnvironment&) = delete;
  CompilerEnvironment& operator=(const CompilerEnvironment&) = delete;
};

/// The compiler's process group (its pid), once it has started; -1 after `limit`.
pid_t compiler_group(const ScratchDir& dir, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = slurp(dir.path() / "cc.pid");
    if (!text.empty()) return static_cast<pid_t>(std::stol(text));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return -1;
}

/// The processes of group `group` that are running (not zombies, which whoever reaps orphans may
/// leave a while), from /proc/PID/stat: "PID (COMM) STATE PPID PGRP …".
std::vector<pid_t> running_in_group(pid_t group) {
  std::vector<pid_t> found;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = slurp(e.path() / "stat");
    const size_t close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    char state = 0;
    long ppid = 0, pgrp = 0;
    if (fields >> state >> ppid >> pgrp && pgrp == group && state != 'Z')
      found.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return found;
}

/// No process of the compiler's group is left running (its shell and its `sleep`).
void expect_no_compiler_left(pid_t group) {
  ASSERT_GT(group, 0);
  for (int i = 0; i < 100 && !running_in_group(group).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(running_in_group(group), std::vector<pid_t>{}) << "the compiler's group still runs";
}

/// Names of the cache's files that are sources or pieces in flight.
std::vector<std::string> leftovers(const ScratchDir& dir) {
  std::vector<std::string> found;
  if (!fs::exists(dir.path() / "cache")) return found;
  for (const auto& e : fs::recursive_directory_iterator(dir.path() / "cache")) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".c" || name.find(".part") != std::string::npos ||
        e.path().extension() == ".log")
      found.push_back(name);
  }
  return found;
}

TEST(CompilerLimits, AHungCompilerIsStoppedAndTheInterpreterRuns) {
  ScratchDir dir("cc-timeout");
  const CompilerEnvironment env(dir, hung_compiler(dir), "1");
  const RunResult r = run_lagrange(dir.path(),
                                   {"simulate", example_path("pendulum.yaml"), "--compile", "on",
                                    "--t-end", "1", "-o", (dir.path() / "out.csv").string()},
                                   std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(r.seconds, 30.0);
  EXPECT_NE(r.err.find("ran for more than 1 s and was stopped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("$LAGRANGE_CC_TIMEOUT"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the tape interpreter runs instead"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("evaluation: interpreter"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir.path() / "out.csv"));
  expect_no_compiler_left(compiler_group(dir, std::chrono::seconds(1)));
  EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
}

// Ctrl-C while `--compile on` compiles: once it waited for the compiler (forever for this one).
// Runs `args` with the hung compiler, sends SIGINT once the compiler has started, and checks the
// run ends at 130 within 5 s, leaving no compiler and a clean cache; its output for more checks.
RunResult interrupted_while_compiling(const ScratchDir& dir, const std::vector<std::string>& args) {
  const CompilerEnvironment env(dir, hung_compiler(dir), nullptr);
  Child child(dir.path(), args);
  const pid_t group = compiler_group(dir, std::chrono::seconds(60));
  EXPECT_GT(group, 0) << "the compiler never started";
  const auto sent = std::chrono::steady_clock::now();
  child.signal(SIGINT);
  const RunResult r = child.wait(std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count(), 5.0);
  if (group > 0) expect_no_compiler_left(group);
  EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
  return r;
}

TEST(CompilerLimits, CtrlCWhileSimulateCompilesEndsAt130) {
  ScratchDir dir("cc-sigint-simulate");
  const RunResult r =
      interrupted_while_compiling(dir, {"simulate", example_path("pendulum.yaml"), "--compile",
                                        "on", "-o", (dir.path() / "out.csv").string()});
  EXPECT_NE(r.err.find("lagrange: interrupted"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out.csv"));
}

TEST(CompilerLimits, CtrlCWhileASweepCompilesEndsAt130) {
  ScratchDir dir("cc-sigint-sweep");
  const RunResult r = interrupted_while_compiling(
      dir, {"sweep", example_path("pendulum.yaml"), "--vary", "m=1,2", "--compile", "on", "-q",
            "-o", (dir.path() / "study").string()});
  EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
}

// export --fmu compiles while Ctrl-C still ends the process at once (nothing is written yet):
// the compiler, in a process group of its own that the terminal's ^C does not reach, is killed
// by the handler before the process ends.
TEST(CompilerLimits, CtrlCWhileAnFmuCompilesLeavesNoCompiler) {
  ScratchDir dir("cc-sigint-fmu");
  const CompilerEnvironment env(dir, hung_compiler(dir), nullptr);
  Child child(dir.path(),
              {"export", example_path("pendulum.yaml"), "--fmu", (dir.path() / "p.fmu").string()});
  const pid_t group = compiler_group(dir, std::chrono::seconds(60));
  ASSERT_GT(group, 0) << "the compiler never started";
  child.signal(SIGINT);
  const RunResult r = child.wait(std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "p.fmu"));
  expect_no_compiler_left(group);
}

}  // namespace
}  // namespace lagrange::hardening
