// libFuzzer target: a metric spec (`--metric`, a model file's `metrics:`) parsed, compiled over a
// pendulum's columns and parameters and evaluated (sweep_input.hpp). StudyError is the expected
// answer for bad text; anything else (crash, sanitizer report, hang, another exception type) is a
// finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "sweep_input.hpp"

namespace {

constexpr size_t kMaxInput = 1 << 14;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInput) return -1;
  (void)lagrange::fuzz::evaluate_metric_spec(
      std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
