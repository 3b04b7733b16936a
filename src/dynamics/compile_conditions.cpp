// What a run records and the conditions over it, compiled with the model: the row's columns, and
// each `lhs < rhs` / `lhs > rhs` of stop_when, fail_when and warn_when as g = rhs − lhs or
// lhs − rhs, positive exactly when it holds (docs/model-language.md, "Stop conditions").
#include <fmt/format.h>

#include "dynamics/row_expression.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/error.hpp"
#include "model/expression_parser.hpp"

namespace lagrange {

namespace {

/// One side of a condition as an expression of the row's names, errors located in the file.
GiNaC::ex parse_side(const StopSpec& spec, const std::string& side, size_t offset,
                     const RowSymbols& names) {
  SourceLoc at = spec.loc;
  try {
    return names.parse(side);
  } catch (const model::ExprError& e) {
    if (at.column > 0) at.column += static_cast<int>(offset + e.offset);
    throw ModelError(at, fmt::format("{} (in stop condition '{}'; the columns and parameters "
                                     "are the names)",
                                     e.message, spec.name));
  }
}

}  // namespace

std::vector<std::string> trajectory_columns(const CompiledModel& cm) {
  std::vector<std::string> cols{"t"};
  for (const auto& q : cm.coordinate_names) cols.push_back(q);
  for (const auto& v : cm.velocity_names) cols.push_back(v);
  cols.insert(cols.end(), {"kinetic", "potential", "energy"});
  for (const auto& o : cm.output_names) cols.push_back(o);
  if (cm.m > 0) {
    for (const auto& c : cm.constraint_names) cols.push_back(c);
    cols.insert(cols.end(), {"constraint_residual", "constraint_rate_residual"});
    for (const auto& r : cm.reaction_names) cols.push_back(r);
  }
  for (const auto& load : cm.loads) cols.push_back(load.name);
  return cols;
}

Tape compile_conditions(const std::vector<StopSpec>& specs, const CompiledModel& cm,
                        const std::vector<std::string>& columns) {
  const RowSymbols names(columns, cm.parameter_names);
  std::vector<GiNaC::ex> g;
  for (const StopSpec& s : specs) {
    const size_t at = s.text.find_first_of("<>");  // the reader checked there is exactly one
    const GiNaC::ex lhs = parse_side(s, s.text.substr(0, at), 0, names);
    const GiNaC::ex rhs = parse_side(s, s.text.substr(at + 1), at + 1, names);
    g.push_back(s.text[at] == '<' ? rhs - lhs : lhs - rhs);
  }
  return Tape::compile(g, names.inputs());
}

}  // namespace lagrange
