// A case's inputs from the study's one traced read of the model file (docs/theory.md §9.4):
// what the reader did with the varied parameters' values, repeated on tapes for the case's.

#include <cmath>
#include <stdexcept>

#include "lagrange/sweep.hpp"

namespace lagrange::sweep {

namespace {

// `e` on a tape over the model's parameters, as the reader evaluates it (model/
// reader_expressions.cpp, in_canonical_order): the same tape, so the same bits.
std::shared_ptr<const Tape> parameter_tape(const GiNaC::ex& e, const Model& m) {
  std::vector<GiNaC::symbol> symbols;
  for (const Parameter& p : m.parameters) symbols.push_back(p.sym);
  return std::make_shared<const Tape>(Tape::compile({e}, symbols));
}

}  // namespace

ReplayedInputs::ReplayedInputs(const Model& traced, const ReadTrace& trace, CaseInput base)
    : base_(std::move(base)) {
  if (!trace.opaque.empty())
    throw std::logic_error(
        "ReplayedInputs: the read used the values where they cannot be "
        "followed: " +
        trace.opaque);
  for (const std::string& name : trace.watched) {
    const int i = traced.parameter_index(name);
    if (i < 0) throw std::logic_error("ReplayedInputs: no parameter " + name);
    watched_.emplace_back(name, static_cast<size_t>(i));
  }
  for (const ReadTrace::Check& c : trace.checks)
    checks_.push_back({parameter_tape(c.value, traced), c.test, c.outcome});
  for (const ReadTrace::Initial& c : trace.initials)
    initials_.push_back({parameter_tape(c.value, traced), c.coordinate, c.rate});
}

std::optional<CaseInput> ReplayedInputs::operator()(
    const std::vector<std::pair<std::string, double>>& values) const {
  CaseInput in = base_;
  for (const auto& [name, value] : values) {
    bool found = false;
    for (const auto& [watched, index] : watched_)
      if (watched == name) {
        in.parameters[index] = value;
        found = true;
      }
    if (!found) throw std::logic_error("ReplayedInputs: '" + name + "' is not watched");
  }
  std::vector<double> work;
  const auto value_of = [&](const Tape& tape) {
    work.resize(tape.work_size());
    double out = 0.0;
    tape.eval(in.parameters.data(), &out, work.data());
    return out;
  };
  for (const Check& c : checks_) {
    const double v = value_of(*c.tape);
    if (!std::isfinite(v) || c.test(v) != c.outcome) return std::nullopt;
  }
  for (const Initial& c : initials_) {
    const double v = value_of(*c.tape);
    if (!std::isfinite(v)) return std::nullopt;
    (c.rate ? in.v0 : in.q0).at(c.coordinate) = v;
  }
  return in;
}

}  // namespace lagrange::sweep
