// docs/model-language.md, "Stop conditions": each `lhs < rhs` / `lhs > rhs` becomes g = rhs − lhs
// or lhs − rhs, positive exactly when it holds, as an expression of the trajectory's columns.
#include "lagrange/stop_conditions.hpp"

#include <fmt/format.h>

#include "lagrange/error.hpp"
#include "model/expression_parser.hpp"
#include "simulation/row_expression.hpp"

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

StopConditions::StopConditions(const CompiledModel& cm, const std::vector<std::string>& columns)
    : StopConditions(cm.stop_when, cm, columns) {}

StopConditions::StopConditions(const std::vector<StopSpec>& specs, const CompiledModel& cm,
                               const std::vector<std::string>& columns)
    : specs_(specs), columns_(columns.size()), parameters_(cm.np) {
  if (specs_.empty()) return;
  const RowSymbols names(columns, cm.parameter_names);
  std::vector<GiNaC::ex> g;
  for (const StopSpec& s : specs_) {
    const size_t at = s.text.find_first_of("<>");  // the reader checked there is exactly one
    const GiNaC::ex lhs = parse_side(s, s.text.substr(0, at), 0, names);
    const GiNaC::ex rhs = parse_side(s, s.text.substr(at + 1), at + 1, names);
    g.push_back(s.text[at] == '<' ? rhs - lhs : lhs - rhs);
  }
  tape_ = Tape::compile(g, names.inputs());
  in_.resize(names.inputs().size());
  work_.resize(tape_.work_size());
}

void StopConditions::evaluate(const double* row, const double* parameters, double* g) const {
  std::copy(row, row + columns_, in_.begin());
  std::copy(parameters, parameters + parameters_, in_.begin() + static_cast<long>(columns_));
  tape_.eval(in_.data(), g, work_.data());
}

}  // namespace lagrange
