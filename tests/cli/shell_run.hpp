#pragma once
// `lagrange ARGS` through the shell, stdout and stderr together: how the command-line tests read
// what a user sees.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "support/test_paths.hpp"

namespace lagrange::testing {

/// Exit code (-1 when the command did not exit normally) and combined output.
struct ShellResult {
  int code;
  std::string output;
};

/// Runs the shell command `command`, stdout and stderr together.
inline ShellResult run_shell_command(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  size_t got;
  while ((got = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), got);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// Runs `lagrange` (LAGRANGE_BINARY) with `args`, a shell-quoted argument string.
inline ShellResult run_shell(const std::string& args) {
  return run_shell_command(std::string(LAGRANGE_BINARY) + " " + args);
}

}  // namespace lagrange::testing
