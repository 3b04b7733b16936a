#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "lagrange/tape.hpp"
#include "model/expression_algebra.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

/// YAML's spellings of infinity and not-a-number (.inf, -.Inf, .NaN, …).
bool is_yaml_nonfinite(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s == ".inf" || s == "+.inf" || s == "-.inf" || s == ".nan";
}

/// e (an expression of parameters) at the parameters' values, evaluated by a tape: evalf adds
/// floating-point terms in GiNaC's order, which changes from process to process, the tape's
/// canonical order does not (docs/errors.md, Determinism). Nothing when the tape cannot be built.
std::optional<double> in_canonical_order(const GiNaC::ex& e,
                                         const std::vector<const Parameter*>& parameters) {
  std::vector<GiNaC::symbol> symbols;
  std::vector<double> values;
  for (const Parameter* p : parameters) {
    symbols.push_back(p->sym);
    values.push_back(p->value);
  }
  try {
    const Tape tape = Tape::compile({e}, symbols);
    std::vector<double> work(tape.work_size());
    double out = 0.0;
    tape.eval(values.data(), &out, work.data());
    return out;
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

/// The parameters whose symbols occur in `e`, in the model's order: found by name, so that
/// evaluating e costs its size, not the number of parameters (issue 37 item 13: reading 10 000
/// parameters took 35 s, each one evaluated with all the others substituted).
std::vector<const Parameter*> parameters_in(const GiNaC::ex& e,
                                            const std::vector<Parameter>& parameters,
                                            const std::map<std::string, NameEntry>& names) {
  std::set<GiNaC::ex, GiNaC::ex_is_less> symbols;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) symbols.insert(*it);
  std::vector<size_t> found;
  for (const GiNaC::ex& sym : symbols) {
    const auto named = names.find(GiNaC::ex_to<GiNaC::symbol>(sym).get_name());
    if (named != names.end() && named->second.kind == NameKind::Parameter &&
        named->second.index < parameters.size() &&
        GiNaC::ex(parameters[named->second.index].sym).is_equal(sym)) {
      found.push_back(named->second.index);
      continue;
    }
    if (named != names.end() && named->second.kind != NameKind::Parameter)
      continue;                                     // a coordinate, an input, …
    for (size_t i = 0; i < parameters.size(); ++i)  // a parameter an element declared
      if (GiNaC::ex(parameters[i].sym).is_equal(sym)) found.push_back(i);
  }
  std::sort(found.begin(), found.end());
  std::vector<const Parameter*> out;
  for (size_t i : found) out.push_back(&parameters[i]);
  return out;
}

}  // namespace

Value ModelReader::parse(const YAML::Node& node, unsigned allowed, const std::string& what,
                         const LocalNames* locals) const {
  if (!node.IsScalar() || node.Scalar().find_first_not_of(" \t\r\n") == std::string::npos)
    fail(node, fmt::format("expected an expression for {}, got {}", what, describe(node)));
  const std::string& text = node.Scalar();
  if (is_yaml_nonfinite(text))
    fail(node, fmt::format("expected a finite number for {}, got '{}'", what, text));
  return parse_text(node, text, allowed, what, locals);
}

Value ModelReader::parse_text(const YAML::Node& node, const std::string& text, unsigned allowed,
                              const std::string& what, const LocalNames* locals) const {
  ParseContext ctx;
  ctx.resolve = [this, allowed, locals](const std::string& name,
                                        size_t offset) -> std::optional<Value> {
    if (locals != nullptr)
      if (auto it = locals->find(name); it != locals->end()) return Value::of(it->second);
    return lookup(name, offset, allowed);
  };
  ctx.time_derivative = [this](const GiNaC::ex& e) { return m_.time_derivative(e); };
  try {
    return parse_expression(text, ctx);
  } catch (const ExprError& e) {
    throw ModelError(src_.at(node, e.offset), fmt::format("{} (in {})", e.message, what));
  }
}

GiNaC::ex ModelReader::scalar_expr(const YAML::Node& node, unsigned allowed,
                                   const std::string& what, const LocalNames* locals) const {
  Value v = parse(node, allowed, what, locals);
  if (v.is_vector || v.is_matrix)
    fail(node, fmt::format("expected a scalar for {}, got {}", what, kind_name(v)));
  return v.scalar;
}

Vec3 ModelReader::vector_expr(const YAML::Node& node, unsigned allowed,
                              const std::string& what) const {
  if (node.IsSequence()) {
    if (node.size() != 3)
      fail(node,
           fmt::format("expected a vector of 3 components for {}, got {}", what, node.size()));
    Vec3 out;
    for (size_t i = 0; i < 3; ++i)
      out[i] = scalar_expr(node[i], allowed, fmt::format("component {} of {}", i + 1, what));
    return out;
  }
  Value v = parse(node, allowed, what);
  if (!v.is_vector)
    fail(node, fmt::format("expected a vector [x, y, z] for {}, got {}", what, kind_name(v)));
  return v.vec;
}

Mat3 ModelReader::matrix_expr(const YAML::Node& node, unsigned allowed,
                              const std::string& what) const {
  if (node.IsSequence()) {
    if (node.size() != 3)
      fail(node, fmt::format("expected a 3×3 matrix [[..], [..], [..]] for {}, got {} rows", what,
                             node.size()));
    Mat3 out;
    for (size_t i = 0; i < 3; ++i)
      out[i] = vector_expr(node[i], allowed, fmt::format("row {} of {}", i + 1, what));
    return out;
  }
  Value v = parse(node, allowed, what);
  if (!v.is_matrix)
    fail(node, fmt::format("expected a 3×3 matrix for {}, got {}", what, kind_name(v)));
  return v.mat;
}

std::optional<double> ModelReader::evaluate(const GiNaC::ex& e) const {
  untraceable(e, "a number the reader computes with");
  return evaluate_unrecorded(e);
}

std::optional<double> ModelReader::evaluate_unrecorded(const GiNaC::ex& e) const {
  try {
    const std::vector<const Parameter*> used = parameters_in(e, m_.parameters, names_);
    GiNaC::exmap values;
    for (const Parameter* p : used) values[p->sym] = GiNaC::numeric(p->value);
    GiNaC::ex r = e.subs(values).evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(r)) return std::nullopt;
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(r);
    if (!n.is_real()) return std::nullopt;
    return in_canonical_order(e, used).value_or(n.to_double());
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<double> ModelReader::replayable_value(const GiNaC::ex& e) const {
  if (!evaluate_unrecorded(e)) return std::nullopt;
  const std::optional<double> v = in_canonical_order(e, parameters_in(e, m_.parameters, names_));
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return v;
}

double ModelReader::number(const YAML::Node& node, unsigned allowed,
                           const std::string& what) const {
  return checked_number(evaluate(scalar_expr(node, allowed, what)), node, what);
}

double ModelReader::checked_number(const std::optional<double>& v, const YAML::Node& node,
                                   const std::string& what) const {
  if (!v)
    fail(node, fmt::format("expected a real number for {}, got '{}'", what, clip(node.Scalar())));
  if (!std::isfinite(*v))
    fail(node, fmt::format("expected a finite number for {}, got '{}'", what, clip(node.Scalar())));
  return *v;
}

void ModelReader::check_sign(const GiNaC::ex& e, const YAML::Node& node, bool strict,
                             const std::string& what) const {
  const std::optional<double> v = evaluate_for_test(
      e, [strict](double x) { return !(std::isfinite(x) && x > 0) && (strict || x != 0); });
  if (!v) return;
  if (std::isfinite(*v) && *v > 0) return;
  if (!strict && *v == 0) return;
  std::string text = clip(node.Scalar()), value = fmt::format("{:g}", *v);
  std::string got = text == value ? value : fmt::format("{} = {}", text, value);
  fail(node,
       fmt::format("expected a {} {}, got {}", strict ? "positive" : "non-negative", what, got));
}

std::string ModelReader::point_name(const YAML::Node& node, const std::string& what) const {
  std::string name = scalar(node, what);
  auto it = names_.find(name);
  if (it == names_.end() ||
      (it->second.kind != NameKind::Point && it->second.kind != NameKind::BodyPoint))
    fail(node, fmt::format("expected a point name for {}, got '{}' (points: {})", what, clip(name),
                           names_of(NameKind::Point)));
  return name;
}

}  // namespace lagrange::model
