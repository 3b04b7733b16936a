// The system C compiler: found as MachineCodeOptions::compiler documents, run without a shell.

#include "compile/c_compiler.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "lagrange/machine_code.hpp"
#include "support/seconds_since.hpp"

extern char** environ;

namespace lagrange {

namespace {

constexpr double kDefaultTimeout = 300.0;

/// The process groups of the compilers running now (0: a free slot), for
/// kill_running_c_compilers; a compile finds no free slot only beyond kSlots at once.
constexpr size_t kSlots = 64;
std::atomic<pid_t> g_running[kSlots];
static_assert(std::atomic<pid_t>::is_always_lock_free, "read from a signal handler");

/// Holds `pid` in a slot of g_running while it lives.
class RunningCompiler {
 public:
  explicit RunningCompiler(pid_t pid) {
    for (auto& slot : g_running) {
      pid_t expected = 0;
      if (slot.compare_exchange_strong(expected, pid)) {
        slot_ = &slot;
        return;
      }
    }
  }
  ~RunningCompiler() {
    if (slot_ != nullptr) slot_->store(0);
  }
  RunningCompiler(const RunningCompiler&) = delete;
  RunningCompiler& operator=(const RunningCompiler&) = delete;

 private:
  std::atomic<pid_t>* slot_ = nullptr;
};

/// The first lines of a compiler log, for the error message.
std::string log_head(const std::string& path) {
  std::ifstream in(path);
  std::string text, line;
  for (int n = 0; n < 6 && std::getline(in, line); ++n) text += "\n  " + line;
  return text;
}

}  // namespace

std::string environment_variable(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::string(v) : std::string();
}

std::string resolve_c_compiler(const std::string& preferred) {
  std::string name = preferred;
  if (name.empty()) name = environment_variable("LAGRANGE_CC");
  if (name.empty()) name = environment_variable("CC");
  if (name.empty()) name = "cc";
  if (name.find('/') != std::string::npos) {
    if (::access(name.c_str(), X_OK) == 0) return name;
    throw MachineCodeError(fmt::format("the C compiler '{}' is not an executable file", name));
  }
  std::stringstream path(environment_variable("PATH"));
  for (std::string dir; std::getline(path, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  throw MachineCodeError(
      fmt::format("no C compiler: '{}' is not on PATH (install one, or set LAGRANGE_CC)", name));
}

void kill_running_c_compilers() {
  for (auto& slot : g_running)
    if (const pid_t pid = slot.load(); pid > 0) ::kill(-pid, SIGKILL);
}

double c_compiler_timeout() {
  const std::string text = environment_variable("LAGRANGE_CC_TIMEOUT");
  char* end = nullptr;
  const double seconds = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  const bool given =
      !text.empty() && end != nullptr && *end == '\0' && seconds > 0 && std::isfinite(seconds);
  return given ? seconds : kDefaultTimeout;
}

void run_c_compiler(const std::string& compiler, const std::vector<std::string>& arguments,
                    const std::string& log_file, const CompilerWatch& watch) {
  std::vector<std::string> args{compiler};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  // A process group of its own, so that the compiler's own children (cc1, as) die with it.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, compiler.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (rc != 0)
    throw MachineCodeError(
        fmt::format("cannot start the C compiler '{}': {}", compiler, std::strerror(rc)));
  const RunningCompiler running(pid);  // until it is reaped below
  const double limit = watch.timeout > 0 ? watch.timeout : c_compiler_timeout();
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR)
      throw MachineCodeError(fmt::format("lost the C compiler: {}", std::strerror(errno)));
    std::string stop;
    if (watch.cancel != nullptr && watch.cancel->load(std::memory_order_relaxed))
      stop = "compilation cancelled";
    else if (watch.interrupted && watch.interrupted())
      stop = "compilation interrupted";
    else if (seconds_since(start) > limit)
      stop = fmt::format(
          "the C compiler '{}' ran for more than {:g} s and was stopped (the limit is "
          "$LAGRANGE_CC_TIMEOUT seconds, {:g} by default)",
          compiler, limit, kDefaultTimeout);
    if (!stop.empty()) {
      ::kill(-pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      throw MachineCodeError(stop);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw MachineCodeError(fmt::format("the C compiler '{}' failed ({}):{}", compiler,
                                       WIFEXITED(status)
                                           ? fmt::format("exit {}", WEXITSTATUS(status))
                                           : fmt::format("signal {}", WTERMSIG(status)),
                                       log_head(log_file)));
}

}  // namespace lagrange
