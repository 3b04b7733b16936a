// Malformed models: each must raise a ModelError at the exact file:line:column naming the culprit.

#include <gtest/gtest.h>

#include <string>

#include "lagrange/reader.hpp"

namespace lagrange {
namespace {

/// One malformed model, where its error must point, and a fragment the message must contain.
struct BadModel {
  const char* label;
  std::string yaml;
  const char* where;  ///< "line:column" in bad.yaml ("" for no line)
  const char* fragment;
};

const std::string kBase = "coordinates:\n  x: {initial: 1}\n";

std::string deep_block_maps() {
  std::string s = kBase + "foo:\n";
  for (int i = 0; i < 300; ++i)
    s += std::string(static_cast<size_t>(2 * i + 2), ' ') + "a" + std::to_string(i) + ":\n";
  return s;
}

/// `n` coordinates in one flow map on line 1.
std::string many_coordinates(int n) {
  std::string s = "coordinates: {";
  for (int i = 0; i < n; ++i) s += (i ? ", q" : "q") + std::to_string(i) + ": {initial: 0}";
  return s + "}\n";
}

std::vector<BadModel> bad_models() {
  return {
      {"yaml syntax", "coordinates:\n  x: {initial: 1\n", "3:1", "syntax error"},
      {"unknown name", kBase + "kinetic: x^2 + foo*3\n", "3:16", "unknown name 'foo'"},
      {"unknown name, quoted", kBase + "kinetic: \"x^2 + foo\"\n", "3:17", "'foo'"},
      {"unknown name, folded", kBase + "kinetic: x^2 +\n   foo*3\n", "4:4", "'foo'"},
      {"unknown name, block", kBase + "kinetic: |\n  x^2 +\n    foo*3\n", "5:5", "'foo'"},
      {"unknown function", kBase + "potential: 2*bessel(x)\n", "3:14", "unknown function 'bessel'"},
      {"vector of 2 in YAML", kBase + "points:\n  p: [1, 2]\n", "4:6",
       "3 components for point 'p', got 2"},
      {"vector of 2 in expression", kBase + "kinetic: dot([1,2], [1,2,3])\n", "3:14",
       "3 components, got 2"},
      {"gravity of 2", kBase + "gravity: [0, -9.81]\n", "3:10", "got 2"},
      {"scalar plus vector", kBase + "kinetic: x + [1,2,3]\n", "3:12", "a scalar + a vector"},
      {"vector for a scalar", kBase + "kinetic: 2*[x, 0, 0]\n", "3:10",
       "expected a scalar for kinetic"},
      {"scalar for a point", kBase + "points:\n  p: x\n", "4:6",
       "expected a vector [x, y, z] for point 'p'"},
      {"missing initial", "coordinates:\n  x: {rate: 1}\n", "2:3", "'initial'"},
      {"missing coordinates", "parameters: {m: 1}\n", "1:1", "'coordinates'"},
      {"duplicate across kinds", "parameters: {x: 1}\n" + kBase, "3:3",
       "'x' which is already the parameter at bad.yaml:1:14"},
      {"point and output share a name", kBase + "points:\n  p: [x,0,0]\noutputs:\n  p: x\n", "6:3",
       "already the point at bad.yaml:4:3"},
      {"duplicate key", kBase + "  x: {initial: 2}\n", "3:3", "'x' again (first at bad.yaml:2:3)"},
      {"name clashes with a velocity", kBase + "parameters: {x_dot: 1}\n", "3:14",
       "got parameter 'x_dot' which is already the derivative of 'x' at bad.yaml:2:3"},
      {"reserved t", "coordinates:\n  t: {initial: 0}\n", "2:3", "'t'"},
      {"shadows a function", "parameters: {sin: 1}\n" + kBase, "1:14",
       "'sin' (it is a built-in function)"},
      {"point through itself", kBase + "points:\n  a: a + [1,0,0]\n", "4:6",
       "'a' defined through itself: a -> a"},
      {"two-point cycle", kBase + "points:\n  a: b + [1,0,0]\n  b: a - [1,0,0]\n", "5:6",
       "a -> b -> a"},
      {"NaN initial", "coordinates:\n  x: {initial: .nan}\n", "2:16",
       "finite number for initial value of coordinate 'x', got '.nan'"},
      {"infinite parameter", "parameters: {g: .inf}\n" + kBase, "1:17", "got '.inf'"},
      {"number overflows", kBase + "kinetic: 1e999*x\n", "3:10", "'1e999'"},
      {"negative mass",
       kBase + "parameters: {m: -2}\npoints:\n  p: [x,0,0]\nparticles:\n  - {point: p, mass: m}\n",
       "7:22", "positive mass for the particle at 'p', got m = -2"},
      {"zero mass", kBase + "points:\n  p: [x,0,0]\nparticles: {p: 0}\n", "5:16", "positive mass"},
      {"negative spring constant",
       kBase + "points:\n  p: [x,0,0]\n  q: [0,0,0]\nsprings:\n  - {between: [p, q], k: -3}\n",
       "7:26", "non-negative spring constant k, got -3"},
      {"negative rest length",
       kBase + "points:\n  p: [x,0,0]\nsprings:\n  - {between: [p, p], k: 1, l0: -1}\n", "6:33",
       "rest length l0, got -1"},
      {"negative damping",
       kBase + "points:\n  p: [x,0,0]\ndampers:\n  - {between: [p, p], c: -0.5}\n", "6:26",
       "damping coefficient c, got -0.5"},
      {"unknown integrator", kBase + "simulate: {integrator: euler}\n", "3:24",
       "unknown integrator 'euler'"},
      {"t_end zero", kBase + "simulate: {t_end: 0}\n", "3:19", "t_end > 0, got 0"},
      {"negative output step", kBase + "simulate: {output_step: -0.1}\n", "3:25",
       "output_step > 0"},
      {"zero rtol", kBase + "simulate: {rtol: 0}\n", "3:18", "rtol > 0"},
      {"fractional BDF order", kBase + "simulate: {max_order: 2.5}\n", "3:23",
       "max_order an integer from 1 to 5 (the BDF methods' highest order), got 2.5"},
      {"BDF order above five", kBase + "simulate: {max_order: 6}\n", "3:23",
       "max_order an integer from 1 to 5"},
      {"empty file", "", "1:1", "got an empty document"},
      {"binary garbage", std::string("\x89PNG\r\n\x1a\n\0\0", 10), "1:1", "binary"},
      {"100000 nested parentheses",
       kBase + "kinetic: " + std::string(100000, '(') + "x" + std::string(100000, ')') + "\n",
       "3:510", "at most 500 levels"},
      {"deep YAML flow sequences",
       kBase + "kinetic: " + std::string(100000, '[') + std::string(100000, ']') + "\n", "3:209",
       "200 levels of YAML nesting"},
      {"deep YAML block maps", deep_block_maps(), "203:401", "200 levels of YAML nesting"},
      {"unknown top-level key", kBase + "gravitty: [0,0,0]\n", "3:1",
       "unknown key 'gravitty' in the model, expected one of: name"},
      {"unknown coordinate in generalized_forces", kBase + "generalized_forces: {y: 1}\n", "3:22",
       "got 'y' (coordinates: x)"},
      {"unknown point in particles", kBase + "particles:\n  - {point: nowhere, mass: 1}\n", "4:13",
       "got 'nowhere' (points: none)"},
      {"unknown point in forces",
       kBase + "points: {p: [x,0,0]}\nforces:\n  - {point: q, force: [1,0,0]}\n", "5:13",
       "got 'q' (points: p)"},
      {"unknown point in springs",
       kBase + "points:\n  p: [x,0,0]\nsprings:\n  - {between: [p, r], k: 1}\n", "6:19", "'r'"},
      {"number where a map is expected", "coordinates: 5\n", "1:14",
       "expected a map for coordinates, got '5'"},
      {"coordinate given as a number", "coordinates:\n  x: 0.5\n", "2:6",
       "expected a map {initial: …, rate: …} for coordinate 'x'"},
      {"unknown coordinate key", "coordinates:\n  x: {initial: 1, rat: 2}\n", "2:19",
       "unknown key 'rat'"},
      {"top level is a list", "- a\n", "1:1", "got a list"},
      {"fixed is not a boolean", "coordinates:\n  x: {initial: 1, fixed: maybe}\n", "2:26",
       "true or false"},
      {"coordinate in an initial value", kBase + "  y: {initial: x}\n", "3:16",
       "got coordinate 'x'"},
      {"input uses a coordinate", kBase + "inputs: {F: x*t}\n", "3:13",
       "got coordinate 'x' (in input 'F')"},
      {"external input without a value", kBase + "inputs: {F: {external: true}}\n", "3:10",
       "expected 'value' in input 'F'"},
      {"external input with an unknown key",
       kBase + "inputs: {F: {value: 0, external: true, hold: 1}}\n", "3:40", "hold"},
      {"external is not a boolean", kBase + "inputs: {F: {value: 0, external: often}}\n", "3:34",
       "true or false"},
      {"external input's value uses a coordinate", kBase + "inputs: {F: {value: x}}\n", "3:21",
       "got coordinate 'x' (in value of input 'F')"},
      {"third derivative", kBase + "kinetic: der(der(der(x)))\n", "3:10",
       "at most second time derivatives"},
      {"constraint used as a value", kBase + "constraints: {rod: x - 1}\noutputs: {o: rod}\n",
       "4:14", "constraint 'rod'"},
      {"velocity written by name", kBase + "kinetic: x_dot^2\n", "3:10", "der(x)"},
      {"division by zero", kBase + "kinetic: x/(1-1)\n", "3:11", "division by zero"},
      {"two documents", kBase + "---\nfoo: 1\n", "3:1", "one YAML document, got more"},
      {"leading comma (yaml-cpp LoadAll loops on it)", ",ame: x\nb: 1\n", "1:1", "got ','"},
      {"unclosed quote", kBase + "potential: \"x^2\n", "3:12", "closing \" for the quoted text"},
      {"too many coordinates", many_coordinates(2500), "1:40905",
       "at most 2000 coordinates, got 2500"},
      {"huge number literal", kBase + "potential: 1" + std::string(100000, '0') + "*x\n", "3:12",
       "finite number, got '1000000000000000000000000000000000000000...'"},
      {"subnormal number", kBase + "potential: 1e-320*x\n", "3:12", "got '1e-320'"},
      {"over-long name", "parameters: {" + std::string(200, 'a') + ": 1}\n" + kBase, "1:14",
       "at most 100 characters"},
      {"apostrophe in a plain scalar is not a quote",
       "name: rock 'n roll\ncoordinates: {x: {initial: 1}}\nfoo: 1\n", "3:1", "unknown key 'foo'"},
      {"empty expression", kBase + "kinetic:   \"\"\n", "3:12",
       "expected an expression for kinetic, got ''"},
      {"stop condition with <=", kBase + "stop_when: {down: x <= 0}\n", "3:19",
       "got '<=' in 'x <= 0': a stop condition fires when its sides cross"},
      {"stop condition with ==", kBase + "stop_when: {down: x == 0}\n", "3:19",
       "write 'lhs < rhs' or 'lhs > rhs'"},
      {"dot(x) for a rate", kBase + "kinetic: dot(x)^2\n", "3:10",
       "a time derivative is written der(x)"},
      {"x' for a rate", kBase + "kinetic: x'^2\n", "3:11", "a time derivative is written der(x)"},
  };
}

class ReaderErrors : public ::testing::TestWithParam<BadModel> {};

TEST_P(ReaderErrors, Located) {
  const BadModel& c = GetParam();
  try {
    read_model_string(c.yaml, "bad.yaml");
    FAIL() << c.label << ": no error";
  } catch (const ModelError& e) {
    std::string where = std::string("bad.yaml:") + c.where;
    EXPECT_EQ(e.loc().str(), where) << c.label << ": " << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(where + ": error: ", 0), 0u) << e.what();
    EXPECT_NE(e.detail().find(c.fragment), std::string::npos) << c.label << ": " << e.what();
    EXPECT_LT(e.detail().size(), 400u) << c.label << ": messages quote, they do not copy the input";
  }
}

std::string test_name(const ::testing::TestParamInfo<BadModel>& info) {
  std::string s;
  for (const char* p = info.param.label; *p; ++p)
    s += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
  return s + "_" + std::to_string(info.index);
}

INSTANTIATE_TEST_SUITE_P(Reader, ReaderErrors, ::testing::ValuesIn(bad_models()), test_name);

TEST(ReaderErrors, RandomBytesNeverCrash) {
  uint32_t state = 12345;
  for (int round = 0; round < 200; ++round) {
    std::string text;
    for (int i = 0; i < 200; ++i) {
      state = state * 1664525u + 1013904223u;
      text += static_cast<char>(round % 2 ? (state >> 24)
                                          : "{}[]:,- \n\"'abx0(#|>&*!"[(state >> 24) % 23]);
    }
    try {
      read_model_string(text, "fuzz.yaml");
    } catch (const ModelError&) {
    }
  }
}

}  // namespace
}  // namespace lagrange
