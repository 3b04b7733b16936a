#pragma once
// Runs the `lagrange` binary in a child process (posix_spawn), with stdout and stderr captured
// to files, and a scratch directory per test (support/scratch_dir.hpp) that is removed afterwards.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/file_text.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_paths.hpp"

extern char** environ;

namespace lagrange::hardening {

namespace fs = std::filesystem;

using lagrange::test::slurp;

/// Writes `text` to `path` byte for byte.
inline void spit(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

/// True when this test (and so the `lagrange` it runs, built alike) has AddressSanitizer.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kUnderAddressSanitizer = true;
#else
constexpr bool kUnderAddressSanitizer = false;
#endif
#else
constexpr bool kUnderAddressSanitizer = false;
#endif

/// What a finished run of the command left behind.
struct RunResult {
  int exit_code = -1;      ///< exit status, or 128 + signal number when killed
  double seconds = 0;      ///< wall time from start to exit (or to the kill at the limit)
  long max_rss_kb = 0;     ///< the child's own peak resident memory (Child::wait says how)
  double cpu_seconds = 0;  ///< the child's user and system time (steadier than wall time)
  std::string out, err;
};

/// A child `lagrange` process started with `args`; its output goes to files in `dir`.
class Child {
 public:
  Child(const fs::path& dir, const std::vector<std::string>& args)
      : dir_(dir), start_(std::chrono::steady_clock::now()) {
    std::vector<std::string> argv{LAGRANGE_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (auto& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    const std::string out = (dir_ / "stdout.txt").string(), err = (dir_ / "stderr.txt").string();
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    struct rusage self {};
    getrusage(RUSAGE_SELF, &self);
    parent_peak_kb_ = self.ru_maxrss;
    const int rc = posix_spawn(&pid_, cargv[0], &fa, nullptr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) throw std::runtime_error("posix_spawn failed for " + argv[0]);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }

  void signal(int sig) const { kill(pid_, sig); }
  /// The process id (to find the processes it started).
  pid_t pid() const { return pid_; }

  /// Caps the child's address space at `bytes` (RLIMIT_AS, set from here at once after the
  /// start): an allocation beyond it fails inside the child instead of swapping the machine.
  /// Not under AddressSanitizer, whose shadow memory reserves terabytes of address space at
  /// start-up: there the caller's check of RunResult::max_rss_kb is the bound.
  void limit_memory(rlim_t bytes) const {
    if (kUnderAddressSanitizer) return;
    const rlimit cap{bytes, bytes};
    if (prlimit(pid_, RLIMIT_AS, &cap, nullptr) != 0)
      throw std::runtime_error("prlimit failed for the child");
  }

  /// Waits for the child (killing it after `limit`) and collects its output.
  ///
  /// The child's peak memory: the kernel's figure for a child (wait4's ru_maxrss) is the larger
  /// of the child's own peak and this process's peak when it started the child (posix_spawn
  /// shares this process's memory until the exec, whose high-water mark the child keeps). When
  /// it exceeds this process's peak it is the child's own; otherwise (a test process grown past
  /// the child's size, as in the sanitizer build's shards) the child's own high-water mark
  /// sampled from /proc every 5 ms while it runs (VmHWM, which only grows) stands instead.
  RunResult wait(std::chrono::seconds limit = std::chrono::seconds(300)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    int status = 0;
    struct rusage usage {};
    long sampled_peak_kb = 0;
    while (wait4(pid_, &status, WNOHANG, &usage) == 0) {
      sampled_peak_kb = std::max(sampled_peak_kb, high_water_mark_kb(pid_));
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid_, SIGKILL);
        wait4(pid_, &status, 0, &usage);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    pid_ = -1;
    RunResult r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    r.max_rss_kb = usage.ru_maxrss > parent_peak_kb_ ? usage.ru_maxrss : sampled_peak_kb;
    r.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(dir_ / "stdout.txt");
    r.err = slurp(dir_ / "stderr.txt");
    fs::remove(dir_ / "stdout.txt");
    fs::remove(dir_ / "stderr.txt");
    return r;
  }

 private:
  /// VmHWM of a running process from /proc/PID/status, in KiB (0 once it has exited).
  static long high_water_mark_kb(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmHWM:", 0) == 0) return std::strtol(line.c_str() + 6, nullptr, 10);
    return 0;
  }

  fs::path dir_;
  std::chrono::steady_clock::time_point start_;
  pid_t pid_ = -1;
  long parent_peak_kb_ = 0;  ///< this process's peak when it started the child
};

/// Runs `lagrange args...` to completion.
inline RunResult run_lagrange(const fs::path& dir, const std::vector<std::string>& args,
                              std::chrono::seconds limit = std::chrono::seconds(300)) {
  return Child(dir, args).wait(limit);
}

using lagrange::test::ScratchDir;

/// A model file with a mistake, and a fragment (usually the offending name) its message must
/// contain.
struct BadModel {
  const char* label;
  std::string yaml;
  const char* fragment;
};

// gtest prints the label instead of the bytes of the struct.
inline void PrintTo(const BadModel& bad, std::ostream* os) {
  *os << bad.label;
}

/// A test name from a case's label: letters and digits kept, everything else '_'.
inline std::string label_name(const ::testing::TestParamInfo<BadModel>& info) {
  std::string s;
  for (const char* c = info.param.label; *c; ++c)
    s += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
  return s;
}

/// What a user meets with a mistaken model: `simulate -o … --plot …` exits 1 with
/// "bad.yaml:line:column: error: …" containing the fragment, quotes rather than copies the
/// input, and writes nothing (no CSV, sidecar, plot or leftover ".part").
inline void expect_model_error(const BadModel& bad, const std::string& scratch) {
  ScratchDir dir(scratch + "-" +
                 std::to_string(static_cast<size_t>(std::hash<std::string>{}(bad.label))));
  const fs::path model = dir.path() / "bad.yaml";
  spit(model, bad.yaml);
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", model.string(), "-o", (dir.path() / "out.csv").string(),
                                "--plot", (dir.path() / "out.svg").string(), "-q"});
  EXPECT_EQ(r.exit_code, 1) << bad.label << "\nstderr: " << r.err.substr(0, 2000);
  EXPECT_TRUE(std::regex_search(r.err, std::regex("bad\\.yaml:[0-9]+:[0-9]+: error: ")))
      << bad.label << "\nstderr: " << r.err.substr(0, 2000);
  EXPECT_NE(r.err.find(bad.fragment), std::string::npos)
      << bad.label << ": expected '" << bad.fragment << "' in\n"
      << r.err.substr(0, 2000);
  EXPECT_LT(r.err.size(), 2000u) << bad.label << ": the message should quote, not copy the input";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.yaml"}) << bad.label;
}

/// The two CSVs a start value should make equal: `simulate` of `model_text` with `--initial
/// initial` (a.csv), and of the same text with `from` replaced by `to` in the file (b.csv); both
/// runs must exit 0.
struct GivenAndWritten {
  fs::path given, written;
};
inline GivenAndWritten run_given_and_written(const ScratchDir& dir, const std::string& model_text,
                                             const std::string& from, const std::string& to,
                                             const std::string& initial) {
  const fs::path model = dir.path() / "model.yaml", file = dir.path() / "written.yaml";
  spit(model, model_text);
  std::string text = model_text;
  text.replace(text.find(from), from.size(), to);
  spit(file, text);
  GivenAndWritten out{dir.path() / "a.csv", dir.path() / "b.csv"};
  const RunResult given = run_lagrange(dir.path(), {"simulate", model.string(), "--initial",
                                                    initial, "-q", "-o", out.given.string()});
  EXPECT_EQ(given.exit_code, 0) << given.err;
  const RunResult written =
      run_lagrange(dir.path(), {"simulate", file.string(), "-q", "-o", out.written.string()});
  EXPECT_EQ(written.exit_code, 0) << written.err;
  return out;
}

}  // namespace lagrange::hardening
