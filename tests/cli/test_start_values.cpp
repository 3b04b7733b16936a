// Start values given to a run (`--initial`, Python `initial=`) or written in the file's
// `initial:` section are the reader's (issue 36 items 1 and 4): a tether's nodes are laid out
// from the ends the run starts at, and every state `trim` prints reads back, in the file and as
// `--initial`, to the same numbers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/prepare.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

// A load on a straight elastic line along x, no gravity: at x the line is stretched uniformly,
// every segment pulls with T = EA (x/L − 1) (docs/theory.md §4.10).
const std::string kElasticLine = R"(parameters: {M: 2, EA: 1000, L: 1}
coordinates:
  x: {initial: 1.05}
points:
  load: [x, 0, 0]
particles: {load: M}
tethers:
  line:
    between: [[0, 0, 0], load]
    segments: 5
    length: L
    mass_per_length: 0.01
    elasticity: {EA: EA}
simulate: {t_end: 0.01, output_step: 0.01}
)";

// A load hanging on a rigid line: trim finds it straight below the anchor.
const std::string kHanging = R"(parameters: {M: 2, L: 1, g: 9.81}
coordinates:
  x: {initial: 0.3}
  z: {initial: -0.9}
points:
  load: [x, 0, z]
particles: {load: M}
gravity: [0, 0, -g]
tethers:
  line:
    between: [[0, 0, 0], load]
    segments: 4
    length: L
    mass_per_length: 0.1
simulate: {t_end: 0.01, output_step: 0.01}
)";

// The first row of a CSV file by column.
std::map<std::string, double> first_row(const fs::path& path) {
  std::istringstream in(slurp(path));
  std::string header, row, field;
  std::getline(in, header);
  std::getline(in, row);
  std::vector<std::string> names;
  for (std::istringstream h(header); std::getline(h, field, ',');) names.push_back(field);
  std::map<std::string, double> out;
  std::istringstream r(row);
  for (const auto& name : names) {
    std::getline(r, field, ',');
    out[name] = std::strtod(field.c_str(), nullptr);
  }
  return out;
}

TEST(StartValues, ElasticLineIsStraightWithUniformTensionAfterInitial) {
  ScratchDir dir("start-elastic");
  const GivenAndWritten runs =
      run_given_and_written(dir, kElasticLine, "initial: 1.05", "initial: 1.1", "x=1.1");
  const auto given = first_row(runs.given), in_file = first_row(runs.written);
  const double expected = 1000 * (1.1 / 1.0 - 1);  // EA (x/L − 1) = 100 N
  for (int j = 1; j <= 5; ++j) {
    const std::string column = "line.tension_" + std::to_string(j);
    EXPECT_NEAR(given.at(column), expected, 1e-9 * expected) << column;
    EXPECT_EQ(given.at(column), in_file.at(column)) << column;
  }
  EXPECT_EQ(given, in_file);
}

TEST(StartValues, PythonInitialLaysTheNodesOnTheMovedEnd) {
  // prepare_source is what the Python module's load(initial=…) calls.
  cli::Prepared p =
      cli::prepare_source(cli::ModelSource{"line.yaml", kElasticLine}, {}, "auto", {{"x", 1.1}});
  const auto& names = p.compiled->coordinate_names;
  for (int j = 1; j < 5; ++j) {
    const auto at = [&](const std::string& name) {
      return static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    const std::string node = "line.node" + std::to_string(j);
    EXPECT_NEAR(p.q.at(at(node + ".x")), 1.1 * j / 5, 1e-15) << node;
    EXPECT_EQ(p.q.at(at(node + ".y")), 0.0) << node;
  }
}

TEST(StartValues, RigidLineKeepsTheLoadWhereInitialPutsIt) {
  ScratchDir dir("start-rigid");
  const fs::path model = dir.path() / "hanging.yaml", csv = dir.path() / "out.csv";
  spit(model, kHanging);
  const RunResult r = run_lagrange(
      dir.path(), {"simulate", model.string(), "--initial", "x=0.6,z=-0.7", "-o", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("projected"), std::string::npos) << r.err;
  const auto row = first_row(csv);
  EXPECT_EQ(row.at("x"), 0.6);
  EXPECT_EQ(row.at("z"), -0.7);
}

// trim's lines, and the values they give: `# as --initial: …`, `coordinates:` and `initial:`.
struct TrimText {
  std::string option, yaml;
  std::map<std::string, double> values;
};

TrimText trim_text(const std::string& out) {
  TrimText t;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# as --initial: ", 0) == 0) t.option = line.substr(16);
    if (line.empty() || line[0] == '#') continue;
    t.yaml += line + "\n";
  }
  std::istringstream pairs(t.option);
  for (std::string pair; std::getline(pairs, pair, ',');) {
    const auto eq = pair.find('=');
    t.values[pair.substr(0, eq)] = std::strtod(pair.c_str() + eq + 1, nullptr);
  }
  return t;
}

TEST(StartValues, WhatTrimPrintsReadsBackInTheFileAndAsInitial) {
  ScratchDir dir("start-trim");
  const fs::path model = dir.path() / "hanging.yaml";
  spit(model, kHanging);
  const RunResult trim = run_lagrange(dir.path(), {"trim", model.string()});
  ASSERT_EQ(trim.exit_code, 0) << trim.err;
  const TrimText t = trim_text(trim.out);
  ASSERT_FALSE(t.option.empty()) << trim.out;
  ASSERT_NE(t.yaml.find("initial:"), std::string::npos) << trim.out;
  // The equilibrium: the line straight down, node j at z = −j L/4.
  EXPECT_NEAR(t.values.at("z"), -1.0, 1e-12);
  EXPECT_NEAR(t.values.at("line.node2.z"), -0.5, 1e-12);
  // Pasted into the file in place of its coordinates: section.
  std::string text = kHanging;
  const auto from = text.find("coordinates:"), to = text.find("points:");
  text.replace(from, to - from, t.yaml);
  const fs::path pasted = dir.path() / "pasted.yaml", a = dir.path() / "a.csv",
                 b = dir.path() / "b.csv";
  spit(pasted, text);
  RunResult r = run_lagrange(dir.path(), {"simulate", pasted.string(), "-o", a.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err << text;
  EXPECT_EQ(r.err.find("projected"), std::string::npos) << r.err;
  r = run_lagrange(dir.path(),
                   {"simulate", model.string(), "--initial", t.option, "-o", b.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("projected"), std::string::npos) << r.err;
  const auto from_file = first_row(a), from_option = first_row(b);
  for (const auto& [name, value] : t.values) {
    EXPECT_EQ(from_file.at(name), value) << name;
    EXPECT_EQ(from_option.at(name), value) << name;
  }
}

TEST(StartValues, AnUnknownNameInTheInitialSectionIsLocated) {
  ScratchDir dir("start-unknown");
  const fs::path model = dir.path() / "hanging.yaml";
  spit(model, kHanging + "initial: {line.node9.x: 0.1}\n");
  const RunResult r = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(
      r.err.find(model.string() + ":16:11: error: expected a coordinate or a rate NAME_dot in "
                                  "initial, got 'line.node9.x'"),
      std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
