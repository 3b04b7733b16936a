// Malformed models through the command line (issue 5): every one must end with exit code 1, a
// message "file:line:column: error: …" naming the culprit, and no output file at all — no CSV, no
// sidecar, no plot, no leftover ".part".

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

/// One bad model and a fragment (usually the offending name) its message must contain.
struct BadModel {
  const char* label;
  std::string yaml;
  const char* fragment;
};

const std::string kBase = "coordinates:\n  x: {initial: 1}\nkinetic: der(x)^2/2\n";
const std::string kPoint = kBase + "points:\n  p: [x, 0, 0]\n";

// A pendulum whose parameters, masses and lengths are given by the caller.
std::string pendulum(const std::string& params, const std::string& mass = "m") {
  return "parameters: " + params +
         "\ncoordinates:\n  theta: {initial: 0.5}\npoints:\n  bob: [l*sin(theta), -l*cos(theta), "
         "0]\n"
         "particles:\n  - {point: bob, mass: " +
         mass + "}\ngravity: [0, -g, 0]\n";
}

// n coordinates in one flow map, each a few bytes: a small file describing an absurd model.
std::string many_coordinates(int n) {
  std::string s = "coordinates: {";
  for (int i = 0; i < n; ++i) s += (i ? ", q" : "q") + std::to_string(i) + ": {initial: 0}";
  return s + "}\npotential: q0^2\n";
}

std::vector<BadModel> bad_models() {
  return {
      // YAML syntax
      {"unclosed flow map", "coordinates:\n  x: {initial: 1\n", "error"},
      {"unclosed quote", kBase + "potential: \"x^2\n", "error"},
      {"bad indentation", "coordinates:\n  x: {initial: 1}\n   y: {initial: 2}\n", "error"},
      {"two documents", kBase + "---\n" + kBase, "document"},
      {"tab indentation", "coordinates:\n\tx: {initial: 1}\n", "forbids tabs"},
      // unknown names
      {"unknown name", kBase + "potential: x^2 + foo*3\n", "'foo'"},
      {"unknown function", kBase + "potential: 2*bessel(x)\n", "'bessel'"},
      {"unknown point in particles", kBase + "particles:\n  - {point: nowhere, mass: 1}\n",
       "'nowhere'"},
      {"unknown point in springs", kPoint + "springs:\n  - {between: [p, r], k: 1}\n", "'r'"},
      {"unknown top-level key", kBase + "gravitty: [0, -9.81, 0]\n", "'gravitty'"},
      {"unknown coordinate key", "coordinates:\n  x: {initial: 1, intial: 2}\n", "'intial'"},
      {"unknown generalized force", kBase + "generalized_forces: {y: 1}\n", "'y'"},
      {"unknown integrator", kBase + "simulate: {integrator: euler}\n", "'euler'"},
      // wrong types
      {"coordinates as a list", "coordinates: [x, y]\n", "coordinates"},
      {"parameter is text", "parameters: {m: heavy}\n" + kBase, "'m'"},
      {"initial is a list", "coordinates:\n  x: {initial: [1, 2]}\n", "'x'"},
      {"potential is a map", kBase + "potential: {a: 1}\n", "potential"},
      {"point is a map", kBase + "points:\n  p: {x: 1}\n", "'p'"},
      // wrong vector sizes
      {"point of 2 components", kBase + "points:\n  p: [x, 0]\n", "'p'"},
      {"gravity of 4 components", kBase + "gravity: [0, -9.81, 0, 1]\n", "gravity"},
      {"dot of unequal vectors", kBase + "potential: dot([x, 1], [x, 1, 0])\n", "got 2"},
      // duplicate names
      {"duplicate coordinate", kBase + "coordinates:\n  y: {initial: 1}\n", "coordinates"},
      {"duplicate key", "coordinates:\n  x: {initial: 1}\n  x: {initial: 2}\n", "'x'"},
      {"parameter named like a coordinate", "parameters: {x: 1}\n" + kBase, "'x'"},
      {"point and output share a name", kPoint + "outputs:\n  p: x\n", "'p'"},
      {"reserved name t", "coordinates:\n  t: {initial: 0}\n", "'t'"},
      {"parameter shadows sin", "parameters: {sin: 1}\n" + kBase, "'sin'"},
      // points defined through themselves
      {"point through itself", kBase + "points:\n  a: a + [1, 0, 0]\n", "'a'"},
      {"two-point cycle", kBase + "points:\n  a: b + [1, 0, 0]\n  b: a - [1, 0, 0]\n",
       "a -> b -> a"},
      // NaN, Inf, negative and zero masses and lengths
      {"NaN initial value", "coordinates:\n  x: {initial: .nan}\n", "'x'"},
      {"infinite parameter", "parameters: {g: .inf}\n" + kBase, "'.inf'"},
      {"NaN mass", pendulum("{l: 1, g: 9.81}", ".nan"), "mass"},
      {"negative mass", pendulum("{m: -2, l: 1, g: 9.81}"), "mass"},
      {"zero mass", pendulum("{m: 0, l: 1, g: 9.81}"), "mass"},
      {"negative spring rest length", kPoint + "springs:\n  - {between: [p, p], k: 1, l0: -1}\n",
       "l0"},
      {"negative spring constant", kPoint + "springs:\n  - {between: [p, p], k: -3}\n", "spring"},
      {"zero-length link", pendulum("{m: 1, l: 0, g: 9.81}"), "'theta'"},
      {"overflowing number", kBase + "potential: 1e999*x\n", "'1e999'"},
      {"bad time step", kBase + "simulate: {output_step: -0.1}\n", "output_step"},
      // empty, binary and absurd files
      {"empty file", "", "empty"},
      {"only a comment", "# nothing here\n", "empty"},
      {"binary file", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "binary"},
      {"NUL byte in text", kBase + std::string("potential: x\0^2\n", 16), "binary"},
      {"100000 nested parentheses",
       kBase + "potential: " + std::string(100000, '(') + "x" + std::string(100000, ')') + "\n",
       "levels"},
      {"100000 nested YAML lists",
       kBase + "outputs: " + std::string(100000, '[') + std::string(100000, ']') + "\n", "nesting"},
      {"100000 coordinates", many_coordinates(100000), "coordinates"},
      {"huge number literal", kBase + "potential: 1" + std::string(100000, '0') + "*x\n", "number"},
      {"alias bomb",
       kBase + "a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
               "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: [*c, *c, *c, *c, *c, *c, *c, *c]\n",
       "'a'"},
      {"lone comma (yaml-cpp loops)", ",\n", "','"},
      {"number to a huge power (fuzz finding)", kBase + "potential: 2^1e30*x\n", "exponent"},
      {"zero to a negative power (fuzz finding)", kBase + "potential: x + 0^-1\n", "exponent of 0"},
      // expressions
      {"expression syntax error", kBase + "potential: x +* 2\n", "'*'"},
      {"unbalanced parenthesis", kBase + "potential: sin(x\n", "')'"},
  };
}

// gtest prints the label instead of the bytes of the struct.
void PrintTo(const BadModel& bad, std::ostream* os) {
  *os << bad.label;
}

class MalformedModel : public ::testing::TestWithParam<BadModel> {};

TEST_P(MalformedModel, Exit1Located) {
  const BadModel& bad = GetParam();
  ScratchDir dir(std::string("malformed-") +
                 std::to_string(static_cast<size_t>(std::hash<std::string>{}(bad.label))));
  const fs::path model = dir.path() / "bad.yaml";
  spit(model, bad.yaml);
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", model.string(), "-o", (dir.path() / "out.csv").string(),
                                "--plot", (dir.path() / "out.svg").string(), "-q"});
  EXPECT_EQ(r.exit_code, 1) << bad.label << "\nstderr: " << r.err.substr(0, 2000);
  EXPECT_TRUE(std::regex_search(r.err, std::regex("bad\\.yaml:[0-9]+:[0-9]+: error: ")))
      << bad.label << "\nstderr: " << r.err.substr(0, 2000);
  EXPECT_NE(r.err.find(bad.fragment), std::string::npos)
      << bad.label << ": expected '" << bad.fragment << "' in\n"
      << r.err.substr(0, 2000);
  EXPECT_LT(r.err.size(), 2000u) << bad.label << ": the message should quote, not copy the input";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.yaml"}) << bad.label;
}

std::string test_name(const ::testing::TestParamInfo<BadModel>& info) {
  std::string s;
  for (const char* c = info.param.label; *c; ++c)
    s += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Cli, MalformedModel, ::testing::ValuesIn(bad_models()), test_name);

TEST(MalformedModelTable, HasAtLeastFortyCases) {
  EXPECT_GE(bad_models().size(), 40u);
}

}  // namespace
}  // namespace lagrange::hardening
