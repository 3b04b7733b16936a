#include "cli/study_record.hpp"

#include <fmt/format.h>

#include <fstream>
#include <set>
#include <sstream>

#include "compile/sha256.hpp"
#include "lagrange/error.hpp"

namespace lagrange::cli {

namespace {

// The bytes of the model file; a UsageError when it cannot be read (it was read moments ago).
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw UsageError(fmt::format("{}: cannot read the model file again", path));
  return bytes.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

std::string study_record(const Options& opt, const CompiledModel& cm,
                         const std::vector<sweep::Metric>& metrics) {
  std::string d = fmt::format("model: {}\n", opt.model);
  d += fmt::format("model file sha256: {}\n", sha256_hex(file_bytes(opt.model)));
  // The tapes as C: the equations whatever files they were read from (a URDF beside the model).
  std::string equations;
  for (const Tape* tape : {&cm.dynamics, &cm.observables, &cm.inputs})
    equations += tape->to_c("f", true);
  d += fmt::format("equations sha256: {}\n", sha256_hex(equations));
  const auto list = [&](const char* option, const std::vector<std::string>& values) {
    for (const auto& v : values) d += fmt::format("{} {}\n", option, v);
  };
  const auto number = [&](const char* option, const std::optional<double>& value) {
    if (value) d += fmt::format("{} {:.17g}\n", option, *value);
  };
  list("--vary", opt.vary);
  list("--random", opt.random);
  if (!opt.random.empty()) d += fmt::format("--samples {}\n--seed {}\n", opt.samples, opt.seed);
  list("--set", opt.sets);
  list("--metric", opt.metrics);
  for (const auto& m : metrics) d += fmt::format("metric {}: {}\n", m.name, m.text);
  number("--t-end", opt.t_end);
  number("--output-step", opt.output_step);
  number("--rtol", opt.rtol);
  number("--atol", opt.atol);
  number("--step", opt.step);
  if (opt.max_order) d += fmt::format("--max-order {}\n", *opt.max_order);
  if (opt.integrator) d += fmt::format("--integrator {}\n", *opt.integrator);
  d += fmt::format("--dynamics {}\n", opt.dynamics);
  if (opt.optimize) {  // what decides an optimisation study's rows (docs/sweeps.md)
    d += fmt::format("--optimize\n--hessian {}\n", opt.hessian);
    if (opt.intervals > 0) d += fmt::format("--intervals {}\n", opt.intervals);
    if (opt.degree > 0) d += fmt::format("--degree {}\n", opt.degree);
    list("--ipopt", opt.ipopt);
  }
  return d;
}

std::string record_changes(const std::string& was, const std::string& now) {
  const std::vector<std::string> before = lines(was), after = lines(now);
  const std::set<std::string> in_before(before.begin(), before.end()),
      in_after(after.begin(), after.end());
  std::string out;
  for (const auto& line : before)
    if (!in_after.count(line)) out += fmt::format("  was: {}\n", line);
  for (const auto& line : after)
    if (!in_before.count(line)) out += fmt::format("  now: {}\n", line);
  return out;
}

}  // namespace lagrange::cli
