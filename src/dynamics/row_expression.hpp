#pragma once
// Expressions over one trajectory row, whose names are the columns and the parameters: what
// `stop_when:` conditions and a study's metrics are written in.

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

namespace lagrange {

/// One symbol per column, then per parameter (a model's one namespace: no name is both).
class RowSymbols {
 public:
  RowSymbols(const std::vector<std::string>& columns, const std::vector<std::string>& parameters);

  /// `text` as a scalar expression of the names (`p.r` stands for the columns p.r.x, p.r.y,
  /// p.r.z). Throws model::ExprError, its offset into `text`, for a syntax error, an unknown
  /// name or a vector or matrix value.
  GiNaC::ex parse(const std::string& text) const;
  /// The tape's inputs: the columns, then the parameters.
  const std::vector<GiNaC::symbol>& inputs() const { return inputs_; }

 private:
  std::map<std::string, GiNaC::symbol> names_;
  std::vector<GiNaC::symbol> inputs_;
};

}  // namespace lagrange
