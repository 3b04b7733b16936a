// A traced read (a study's): which of the model's numbers depend on the watched parameters'
// values, and how, so that a case with other values needs no new read (docs/theory.md §9.4).

#include "lagrange/rigid_body.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

bool ModelReader::traced(const GiNaC::ex& e) const {
  if (trace_ == nullptr || traced_symbols_.empty()) return false;
  for (const GiNaC::symbol& s : traced_symbols_)
    if (e.has(s)) return true;
  // An input's value is its expression's (of parameters and t only).
  for (const Input& u : m_.inputs)
    if ((e.has(u.u) || e.has(u.ud) || e.has(u.udd)) && traced(u.expr)) return true;
  return false;
}

void ModelReader::untraceable(const GiNaC::ex& e, const std::string& what) const {
  if (trace_ != nullptr && trace_->opaque.empty() && traced(e)) trace_->opaque = what;
}

std::optional<double> ModelReader::evaluate_for_test(
    const GiNaC::ex& e, const std::function<bool(double)>& test) const {
  if (!traced(e)) return evaluate_unrecorded(e);
  const std::optional<double> v = replayable_value(e);
  if (!v) {
    untraceable(e, "a value that is not a finite number");
    return evaluate_unrecorded(e);
  }
  trace_->checks.push_back({e, test, test(*v)});
  return v;
}

double ModelReader::coordinate_number(const YAML::Node& node, const std::string& what,
                                      const Coordinate& c, bool rate) {
  const GiNaC::ex e = scalar_expr(node, kParams, what);
  if (traced(e)) {
    if (const std::optional<double> v = replayable_value(e)) {
      trace_->initials.push_back({m_.coordinates.size(), rate, e});
      traced_symbols_.push_back(rate ? c.v : c.q);
      return *v;
    }
    untraceable(e, what);
  }
  return checked_number(evaluate_unrecorded(e), node, what);
}

void ModelReader::watch_parameters() {
  if (trace_ == nullptr) return;
  for (const std::string& name : trace_->watched)
    if (const int i = m_.parameter_index(name); i >= 0)
      traced_symbols_.push_back(m_.parameters[static_cast<size_t>(i)].sym);
}

void ModelReader::check_inertia(const Body& body, std::optional<size_t> spin_axis) const {
  untraceable(body.mass, "the mass of body '" + body.name + "'");
  for (const Vec3& row : body.inertia)
    for (const GiNaC::ex& e : row) untraceable(e, "the inertia of body '" + body.name + "'");
  check_body_inertia(m_, body, spin_axis);
}

}  // namespace lagrange::model
