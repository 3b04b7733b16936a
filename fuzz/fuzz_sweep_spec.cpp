// libFuzzer target: the sweep's `--vary` and `--random` parsers and the case expansion behind
// them (sweep_input.hpp). StudyError is the expected answer for bad text; anything else (crash,
// sanitizer report, hang, runaway allocation, another exception type) is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "sweep_input.hpp"

namespace {

constexpr size_t kMaxInput = 1 << 12;  // a spec is one argument of a command line

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInput) return -1;
  (void)lagrange::fuzz::parse_sweep_spec(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
