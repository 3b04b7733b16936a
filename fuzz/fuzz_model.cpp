// libFuzzer target: a whole YAML model file → read_model_string, then derive + compile when the
// model is small (model_budget.hpp). Any ModelError is a correct answer; every other exception,
// crash, sanitizer report, hang or runaway allocation is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/error.hpp"
#include "lagrange/reader.hpp"
#include "model_budget.hpp"

namespace {
constexpr size_t kMaxInput = 4096;  // model files the fuzzer writes stay readable and fast
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInput) return -1;  // reject: not added to the corpus
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const lagrange::Model model = lagrange::read_model_string(text, "fuzz.yaml");
    if (!lagrange::fuzz::fits(model, lagrange::fuzz::Budget{})) return 0;
    const lagrange::Equations eq = lagrange::derive(model);
    (void)lagrange::compile(eq);
  } catch (const lagrange::ModelError&) {
    // a diagnosed mistake in the model: the expected outcome for most inputs
  }
  return 0;
}
