// Expressions over a trajectory row (src/dynamics/row_expression.hpp).

#include "dynamics/row_expression.hpp"

#include "model/expression_parser.hpp"

namespace lagrange {

RowSymbols::RowSymbols(const std::vector<std::string>& columns,
                       const std::vector<std::string>& parameters) {
  for (const auto* list : {&columns, &parameters})
    for (const std::string& name : *list)
      inputs_.push_back(names_.emplace(name, GiNaC::symbol(name)).first->second);
}

GiNaC::ex RowSymbols::parse(const std::string& text) const {
  model::ParseContext ctx;
  ctx.resolve = [this](const std::string& name, size_t) -> std::optional<model::Value> {
    if (auto it = names_.find(name); it != names_.end()) return model::Value::of(it->second);
    // `p.r` for the columns p.r.x, p.r.y, p.r.z (any vector-valued output).
    const auto x = names_.find(name + ".x"), y = names_.find(name + ".y"),
               z = names_.find(name + ".z");
    if (x != names_.end() && y != names_.end() && z != names_.end())
      return model::Value::of(Vec3{x->second, y->second, z->second});
    return std::nullopt;
  };
  const model::Value v = model::parse_expression(text, ctx);
  if (v.is_vector || v.is_matrix)
    throw model::ExprError{0, "expected a scalar, got a vector or matrix"};
  return v.scalar;
}

}  // namespace lagrange
