// docs/model-language.md, "Stop conditions": each `lhs < rhs` / `lhs > rhs` becomes g = rhs − lhs
// or lhs − rhs, positive exactly when it holds, as an expression of the trajectory's columns.
#include "lagrange/stop_conditions.hpp"

#include <fmt/format.h>

#include <map>

#include "lagrange/error.hpp"
#include "model/expression_parser.hpp"

namespace lagrange {

namespace {

/// One side of a condition, parsed with names resolving to column or parameter symbols.
GiNaC::ex parse_side(const StopSpec& spec, const std::string& side, size_t offset,
                     const std::map<std::string, GiNaC::symbol>& names) {
  model::ParseContext ctx;
  ctx.resolve = [&names](const std::string& name, size_t) -> std::optional<model::Value> {
    if (auto it = names.find(name); it != names.end()) return model::Value::of(it->second);
    // `p.r` for the columns p.r.x, p.r.y, p.r.z (any vector-valued output).
    const auto x = names.find(name + ".x"), y = names.find(name + ".y"),
               z = names.find(name + ".z");
    if (x != names.end() && y != names.end() && z != names.end())
      return model::Value::of(Vec3{x->second, y->second, z->second});
    return std::nullopt;
  };
  SourceLoc at = spec.loc;
  try {
    const model::Value v = model::parse_expression(side, ctx);
    if (v.is_vector || v.is_matrix)
      throw model::ExprError{0, "expected a scalar on each side, got a vector or matrix"};
    return v.scalar;
  } catch (const model::ExprError& e) {
    if (at.column > 0) at.column += static_cast<int>(offset + e.offset);
    throw ModelError(at, fmt::format("{} (in stop condition '{}'; the columns and parameters "
                                     "are the names)",
                                     e.message, spec.name));
  }
}

}  // namespace

StopConditions::StopConditions(const CompiledModel& cm, const std::vector<std::string>& columns)
    : StopConditions(cm.stop_when, cm, columns) {}

StopConditions::StopConditions(const std::vector<StopSpec>& specs, const CompiledModel& cm,
                               const std::vector<std::string>& columns)
    : specs_(specs), columns_(columns.size()), parameters_(cm.np) {
  if (specs_.empty()) return;
  std::map<std::string, GiNaC::symbol> names;
  std::vector<GiNaC::symbol> inputs;
  // Columns and parameters share the model's one namespace, so no name is both.
  for (const std::string& c : columns) inputs.push_back(names.emplace(c, c).first->second);
  for (const std::string& p : cm.parameter_names)
    inputs.push_back(names.emplace(p, p).first->second);
  std::vector<GiNaC::ex> g;
  for (const StopSpec& s : specs_) {
    const size_t at = s.text.find_first_of("<>");  // the reader checked there is exactly one
    const GiNaC::ex lhs = parse_side(s, s.text.substr(0, at), 0, names);
    const GiNaC::ex rhs = parse_side(s, s.text.substr(at + 1), at + 1, names);
    g.push_back(s.text[at] == '<' ? rhs - lhs : lhs - rhs);
  }
  tape_ = Tape::compile(g, inputs);
  in_.resize(inputs.size());
  work_.resize(tape_.work_size());
}

void StopConditions::evaluate(const double* row, const double* parameters, double* g) const {
  std::copy(row, row + columns_, in_.begin());
  std::copy(parameters, parameters + parameters_, in_.begin() + static_cast<long>(columns_));
  tape_.eval(in_.data(), g, work_.data());
}

}  // namespace lagrange
