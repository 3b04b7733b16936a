#pragma once
// The system C compiler, shared by machine code (machine_code.cpp) and FMU export.

#include <atomic>
#include <string>
#include <vector>

namespace lagrange {

/// The compiler's full path: `preferred` when not empty, else $LAGRANGE_CC, else $CC, else `cc`;
/// a name with a slash is taken as a path, others are looked up on PATH (MachineCodeError if none).
std::string resolve_c_compiler(const std::string& preferred);

/// Runs `compiler arguments…` (no shell; stdin /dev/null, stdout and stderr into `log_file`),
/// polling `cancel` every 10 ms and killing the compiler when it is set. MachineCodeError with the
/// log's first lines when it fails.
void run_c_compiler(const std::string& compiler, const std::vector<std::string>& arguments,
                    const std::string& log_file, const std::atomic<bool>* cancel = nullptr);

}  // namespace lagrange
