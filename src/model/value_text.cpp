// A value written outside a model file (`--set`, `--initial`, `--vary`, Python), read as the file
// reads one (docs/model-language.md): numbers, pi, the functions and the names a caller allows.

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "lagrange/reader.hpp"
#include "lagrange/tape.hpp"
#include "model/expression_algebra.hpp"
#include "model/expression_parser.hpp"

namespace lagrange {

namespace {

/// "(names here: pi, a, b)": what a value may name, for a message.
std::string known_names(const std::map<std::string, double>& names) {
  std::string text = "pi";
  for (const auto& [name, value] : names) text += ", " + name;
  return names.empty() ? "(a value here may use numbers, pi and functions, no names)"
                       : fmt::format("(names here: {})", text);
}

}  // namespace

double evaluate_value_text(const std::string& text, const std::map<std::string, double>& names) {
  std::vector<GiNaC::symbol> symbols;
  std::vector<double> values;
  std::map<std::string, GiNaC::ex> by_name;
  for (const auto& [name, value] : names) {
    symbols.emplace_back(name);
    values.push_back(value);
    by_name[name] = symbols.back();
  }
  model::ParseContext ctx;
  ctx.resolve = [&by_name](const std::string& name, size_t) -> std::optional<model::Value> {
    if (auto it = by_name.find(name); it != by_name.end()) return model::Value::of(it->second);
    return std::nullopt;
  };
  model::Value v;
  try {
    v = model::parse_expression(text, ctx);
  } catch (const model::ExprError& e) {
    const bool unknown = e.message.rfind("unknown name", 0) == 0;
    throw ValueTextError(fmt::format("{} at character {} of '{}'{}", e.message, e.offset + 1,
                                     model::clip(text),
                                     unknown ? " " + known_names(names) : std::string()));
  }
  if (v.is_vector || v.is_matrix)
    throw ValueTextError(
        fmt::format("expected a number, got {} '{}'", model::kind_name(v), model::clip(text)));
  // Evaluated by a tape, as the reader evaluates parameter expressions (canonical order).
  double out = NAN;
  try {
    const Tape tape = Tape::compile({v.scalar}, symbols);
    std::vector<double> work(tape.work_size());
    tape.eval(values.data(), &out, work.data());
  } catch (const std::invalid_argument&) {
    out = NAN;
  }
  if (!std::isfinite(out))
    throw ValueTextError(
        fmt::format("expected a finite real number, got '{}' = {}", model::clip(text), out));
  return out;
}

}  // namespace lagrange
