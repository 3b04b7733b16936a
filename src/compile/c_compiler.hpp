#pragma once
// The system C compiler, shared by machine code (machine_code.cpp) and FMU export.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace lagrange {

/// The environment variable `name`, or "" when it is not set.
std::string environment_variable(const char* name);

/// The compiler's full path: `preferred` when not empty, else $LAGRANGE_CC, else $CC, else `cc`;
/// a name with a slash is taken as a path, others are looked up on PATH (MachineCodeError if none).
std::string resolve_c_compiler(const std::string& preferred);

/// What stops a running compiler early, checked every 10 ms.
struct CompilerWatch {
  const std::atomic<bool>* cancel = nullptr;  ///< set: stopped ("compilation cancelled")
  std::function<bool()> interrupted;          ///< true: stopped ("interrupted")
  double timeout = 0.0;                       ///< seconds; 0: c_compiler_timeout()
};

/// The compiler's time limit in seconds: $LAGRANGE_CC_TIMEOUT when it is a positive number, else
/// 300 (docs/errors.md, "Machine code").
double c_compiler_timeout();

/// Runs `compiler arguments…` (no shell; stdin /dev/null, stdout and stderr into `log_file`) in a
/// process group of its own, which is killed whole when `watch` stops it or it runs past its time
/// limit. MachineCodeError with the log's first lines when it fails, saying why it was stopped.
void run_c_compiler(const std::string& compiler, const std::vector<std::string>& arguments,
                    const std::string& log_file, const CompilerWatch& watch = {});

/// Kills the process group of every compiler run_c_compiler is running (async-signal-safe): for
/// a SIGINT handler that ends the process with _exit, which would leave them running.
void kill_running_c_compilers();

}  // namespace lagrange
