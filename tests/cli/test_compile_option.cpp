// `simulate --compile on|off|auto` as a user meets it (docs/theory.md §8, machine code): the same
// CSV, byte for byte, whatever evaluates the tapes; a missing compiler is said once and the run
// goes on; a bad value is a usage error.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::example_path;

/// Runs lagrange with LAGRANGE_CACHE_DIR (and optionally LAGRANGE_CC) set for the child only.
RunResult run_with(const ScratchDir& dir, const std::vector<std::string>& args,
                   const char* compiler = nullptr) {
  ::setenv("LAGRANGE_CACHE_DIR", (dir.path() / "cache").c_str(), 1);
  if (compiler != nullptr) ::setenv("LAGRANGE_CC", compiler, 1);
  RunResult r = run_lagrange(dir.path(), args);
  ::unsetenv("LAGRANGE_CACHE_DIR");
  ::unsetenv("LAGRANGE_CC");
  return r;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(CompileOption, MachineCodeWritesTheSameCsvAsTheInterpreter) {
  const ScratchDir dir("compile-same-csv");
  const std::string model = example_path("five_bar.yaml");
  const RunResult off = run_with(dir, {"simulate", model, "--t-end", "2", "--compile", "off", "-o",
                                       (dir.path() / "off.csv").string()});
  const RunResult on = run_with(dir, {"simulate", model, "--t-end", "2", "--compile", "on", "-o",
                                      (dir.path() / "on.csv").string()});
  ASSERT_EQ(off.exit_code, 0) << off.err;
  ASSERT_EQ(on.exit_code, 0) << on.err;
  EXPECT_NE(off.out.find("evaluation: interpreter"), std::string::npos) << off.out;
  EXPECT_NE(on.out.find("evaluation: machine code (compiled in"), std::string::npos) << on.out;
  const std::string csv = slurp(dir.path() / "off.csv");
  EXPECT_GT(csv.size(), 1000u);
  EXPECT_EQ(slurp(dir.path() / "on.csv"), csv);
  const RunResult again = run_with(dir, {"simulate", model, "--t-end", "2", "--compile", "on", "-o",
                                         (dir.path() / "again.csv").string()});
  EXPECT_NE(again.out.find("evaluation: machine code (from the cache)"), std::string::npos)
      << again.out;
}

TEST(CompileOption, MissingCompilerIsSaidOnceAndTheRunGoesOn) {
  const ScratchDir dir("compile-no-cc");
  const RunResult r = run_with(dir,
                               {"simulate", example_path("double_pendulum.yaml"), "--t-end", "1",
                                "--compile", "on", "-o", (dir.path() / "dp.csv").string()},
                               "no-such-compiler-for-lagrange");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.err, "no C compiler: 'no-such-compiler-for-lagrange' is not on PATH"), 1u)
      << r.err;
  EXPECT_NE(r.err.find("the tape interpreter runs instead"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "dp.csv"));
}

TEST(CompileOption, TamperedCacheEntriesAreRecompiledAndTheAnswerIsRight) {
  const ScratchDir dir("compile-tampered");
  const auto run = [&](const std::string& model, const std::string& csv) {
    return run_with(dir, {"simulate", example_path(model), "--t-end", "1", "--compile", "on", "-o",
                          (dir.path() / csv).string()});
  };
  const auto library = [&] {
    std::vector<fs::path> found;
    for (const auto& e : fs::directory_iterator(dir.path() / "cache"))
      if (e.path().extension() == ".so") found.push_back(e.path());
    EXPECT_EQ(found.size(), 1u);
    return found.at(0);
  };
  ASSERT_EQ(run("double_pendulum.yaml", "good.csv").exit_code, 0);
  const fs::path mine = library();
  const std::string good = slurp(dir.path() / "good.csv");
  // Truncated (was SIGBUS), then another model's library and record under this name (SIGSEGV).
  fs::resize_file(mine, fs::file_size(mine) / 3);
  const RunResult truncated = run("double_pendulum.yaml", "truncated.csv");
  const fs::path moved = dir.path() / "mine.so";
  fs::rename(mine, moved);
  fs::rename(mine.string() + ".sha256", moved.string() + ".sha256");
  ASSERT_EQ(run("pendulum.yaml", "other.csv").exit_code, 0);
  const fs::path other = library();
  fs::copy_file(other, mine);
  fs::copy_file(other.string() + ".sha256", mine.string() + ".sha256");
  const RunResult foreign = run("double_pendulum.yaml", "foreign.csv");
  for (const RunResult* r : {&truncated, &foreign}) {
    EXPECT_EQ(r->exit_code, 0) << r->err;
    EXPECT_NE(r->out.find("does not match its recorded SHA-256 (truncated, replaced or another "
                          "model's); recompiled"),
              std::string::npos)
        << r->out;
  }
  EXPECT_EQ(slurp(dir.path() / "truncated.csv"), good);
  EXPECT_EQ(slurp(dir.path() / "foreign.csv"), good);
}

TEST(CompileOption, CacheDirectoryOthersCanWriteIsNotUsed) {
  const ScratchDir dir("compile-open-cache");
  fs::create_directory(dir.path() / "cache");
  fs::permissions(dir.path() / "cache", fs::perms::all);
  const RunResult r =
      run_with(dir, {"simulate", example_path("double_pendulum.yaml"), "--t-end", "1", "--compile",
                     "on", "-o", (dir.path() / "dp.csv").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("is writable by group or others (mode 0777): code in it is not loaded"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("evaluation: interpreter"), std::string::npos) << r.out;
  EXPECT_EQ(fs::directory_iterator(dir.path() / "cache"), fs::directory_iterator());
}

TEST(CompileOption, UnknownValueIsAUsageError) {
  const ScratchDir dir("compile-bad-value");
  const RunResult r =
      run_with(dir, {"simulate", example_path("pendulum.yaml"), "--compile", "sometimes"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--compile"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
