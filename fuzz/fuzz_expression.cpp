// libFuzzer target: one expression in the model language, parsed on its own by
// parse_expression with a resolver that knows a few scalar and vector names. ExprError is the
// expected answer for bad text; anything else (crash, sanitizer report, stack overflow, hang,
// another exception type) is a finding.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "model/expression_lexer.hpp"
#include "model/expression_parser.hpp"

namespace {

constexpr size_t kMaxInput = 1 << 17;  // room for 100 000 nested parentheses

struct Symbols {
  GiNaC::symbol t{"t"}, x{"x"}, y{"y"}, m{"m"}, l{"l"};
};

std::optional<lagrange::model::Value> resolve(const Symbols& s, const std::string& name) {
  using lagrange::model::Value;
  if (name == "t") return Value::of(GiNaC::ex(s.t));
  if (name == "x") return Value::of(GiNaC::ex(s.x));
  if (name == "y") return Value::of(GiNaC::ex(s.y));
  if (name == "m") return Value::of(GiNaC::ex(s.m));
  if (name == "l") return Value::of(GiNaC::ex(s.l));
  if (name == "p") return Value::of(lagrange::Vec3{s.x, s.y, 0});
  if (name == "r")
    return Value::of(lagrange::Vec3{s.l * GiNaC::sin(s.x), -s.l * GiNaC::cos(s.x), 0});
  return std::nullopt;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInput) return -1;
  static const Symbols symbols;
  const std::string text(reinterpret_cast<const char*>(data), size);
  lagrange::model::ParseContext ctx;
  ctx.resolve = [](const std::string& name, size_t) { return resolve(symbols, name); };
  ctx.time_derivative = [](const GiNaC::ex& e) {
    // d/dt with x, y moving at unit rate: enough for der()/vel() to exercise their paths
    return e.diff(symbols.t) + e.diff(symbols.x) + e.diff(symbols.y);
  };
  try {
    (void)lagrange::model::parse_expression(text, ctx);
  } catch (const lagrange::model::ExprError&) {
    // a diagnosed mistake in the expression
  }
  (void)lagrange::model::referenced_names(text);
  return 0;
}
