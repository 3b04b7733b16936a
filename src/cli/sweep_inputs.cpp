// The cases' inputs of a study: one traced read of the model file replayed for every case, or
// each case's own read (docs/theory.md §9.4).

#include "cli/sweep_inputs.hpp"

#include <fmt/format.h>

#include <cstring>

#include "cli/commands.hpp"
#include "lagrange/error.hpp"

namespace lagrange::cli {

namespace {

ParameterOverrides with_values(const CaseInputSource& from, const CaseValues& values) {
  ParameterOverrides all = from.fixed;
  for (const auto& [name, value] : values) all[name] = value;
  return all;
}

Model traced_read(const ModelSource& source, const ParameterOverrides& values, ReadTrace& trace) {
  return source.text ? read_model_string(*source.text, source.path, values, &trace)
                     : read_model_file(source.path, values, trace);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool same_inputs(const sweep::CaseInput& a, const sweep::CaseInput& b) {
  return same_bits(a.parameters, b.parameters) && same_bits(a.q0, b.q0) && same_bits(a.v0, b.v0) &&
         same_bits({a.baumgarte}, {b.baumgarte});
}

}  // namespace

sweep::CaseRead read_case_inputs(const CaseInputSource& from, const CaseValues& values) {
  sweep::CaseRead r;
  try {
    r.input = from.inputs_of(from.source.read(with_values(from, values)));
  } catch (const ModelError& e) {
    r.rejected = fmt::format("the model does not accept these values: {} (at {})", e.detail(),
                             e.loc().str());
  } catch (const UsageError& e) {
    r.rejected = e.what();
  } catch (const sweep::StudyError& e) {
    r.rejected = e.what();
  }
  return r;
}

StudyReplay replay_study(const CaseInputSource& from, const std::vector<CaseValues>& cases) {
  StudyReplay s;
  ReadTrace trace;
  for (const auto& [name, value] : cases.at(0)) trace.watched.push_back(name);
  std::optional<sweep::CaseInput> base;
  std::optional<Model> traced;
  ++s.reads;
  try {
    traced.emplace(traced_read(from.source, with_values(from, cases[0]), trace));
    base = from.inputs_of(*traced);
  } catch (const std::exception&) {
    s.not_replayed = "the first case's values are rejected";
    return s;
  }
  if (!trace.opaque.empty()) {
    s.not_replayed = trace.opaque + " depends on the varied parameters";
    return s;
  }
  s.inputs.emplace(*traced, trace, std::move(*base));
  size_t last = cases.size();  // the last case (after the first) it gives
  std::optional<sweep::CaseInput> replayed;
  while (!replayed && --last > 0) replayed = (*s.inputs)(cases[last]);
  if (!replayed) return s;
  ++s.reads;
  const sweep::CaseRead read = read_case_inputs(from, cases[last]);
  if (read.input && same_inputs(*replayed, *read.input)) return s;
  s.inputs.reset();
  s.not_replayed = "the inputs from one read differ from the last case's own read";
  s.warning = fmt::format(
      "the inputs of case {} computed from one read of {} differ from its own read; every "
      "case's model file is read instead (please report this)",
      last, from.source.path);
  return s;
}

}  // namespace lagrange::cli
