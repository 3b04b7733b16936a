// A study's cases' inputs from one traced read of the model file (docs/theory.md §9.4): equal,
// bit for bit, to a read with each case's values; a check that comes out otherwise sends the
// case back to the file, and a use of the values the trace cannot follow (a tether's shape) the
// whole study.

#include <gtest/gtest.h>

#include <cstring>

#include "lagrange/compiled_model.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::sweep {
namespace {

// Initial values and rates written as expressions of the varied a and c, a mass m that must be
// positive, an angle-only parameter th that warns beyond a turn.
const std::string kReplayedModel = R"(
parameters: {a: 0.7, m: 2, c: 0.3, th: 0.5}
coordinates:
  x: {initial: a*sin(a) + 1/3, rate: -a/7}
  y: {initial: 0.25 + c*exp(c)}
points:
  p: [x*cos(th), y, 0]
particles:
  - {point: p, mass: m}
gravity: [0, -9.81, 0]
)";

// What case_input takes from a model: its parameters' values and initial state.
CaseInput inputs_of(const Model& m) {
  CaseInput in;
  const ModelInitialState s = model_initial_state(m);
  in.q0 = s.q0;
  in.v0 = s.v0;
  for (const Parameter& p : m.parameters) in.parameters.push_back(p.value);
  return in;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

using Values = std::vector<std::pair<std::string, double>>;

ParameterOverrides overrides(const Values& v) {
  return {v.begin(), v.end()};
}

TEST(ReplayedInputs, EqualAReadWithTheCaseValuesBitForBit) {
  ReadTrace trace;
  trace.watched = {"a", "m", "c", "th"};
  const Values first{{"a", 0.7}, {"m", 2}, {"c", 0.3}, {"th", 0.5}};
  const Model m = read_model_string(kReplayedModel, "replay.yaml", overrides(first), &trace);
  ASSERT_TRUE(trace.opaque.empty()) << trace.opaque;
  EXPECT_EQ(trace.initials.size(), 3u);  // x and its rate, y
  EXPECT_EQ(trace.checks.size(), 2u);    // m > 0, |th| within a turn
  const ReplayedInputs replay(m, trace, inputs_of(m));
  for (const Values& v : {first, Values{{"a", 1.9}, {"m", 0.5}, {"c", -2.0 / 3}, {"th", -1}},
                          Values{{"a", -0.3}, {"m", 7}, {"c", 1e-3}, {"th", 6.2}}}) {
    const std::optional<CaseInput> in = replay(v);
    ASSERT_TRUE(in) << v[0].second;
    const CaseInput read =
        inputs_of(read_model_string(kReplayedModel, "replay.yaml", overrides(v)));
    EXPECT_TRUE(same_bits(in->q0, read.q0)) << v[0].second;
    EXPECT_TRUE(same_bits(in->v0, read.v0)) << v[0].second;
    EXPECT_TRUE(same_bits(in->parameters, read.parameters)) << v[0].second;
  }
  // A mass the model refuses, an angle it warns about: only the file says what follows.
  EXPECT_FALSE(replay({{"a", 0.7}, {"m", -1}, {"c", 0.3}, {"th", 0.5}}));
  EXPECT_THROW(read_model_string(kReplayedModel, "replay.yaml", {{"m", -1}}), ModelError);
  EXPECT_FALSE(replay({{"a", 0.7}, {"m", 2}, {"c", 0.3}, {"th", 7}}));
  // Not a number at all (log of a negative x): the file's read refuses it.
  EXPECT_FALSE(replay({{"a", 0.7}, {"m", 2}, {"c", 1e300}, {"th", 0.5}}));
}

// A tether's nodes are placed by the reader from its length and its ends' initial positions:
// a trace follows neither, so a study varying them reads every case's file.
TEST(ReplayedInputs, ATethersShapeIsNotFollowed) {
  const std::string tether = R"(
parameters: {L: 3, mu: 0.01, c: 1}
coordinates:
  x: {initial: 2, rate: 0}
  y: {initial: 0}
  z: {initial: -c}
points:
  p: [x, y, z]
particles:
  - {point: p, mass: 1}
gravity: [0, 0, -9.81]
tethers:
  line: {between: [[0, 0, 0], p], segments: 2, mass_per_length: mu, length: L}
)";
  for (const char* varied : {"L", "c"}) {
    ReadTrace trace;
    trace.watched = {varied};
    read_model_string(tether, "tether.yaml", {}, &trace);
    EXPECT_NE(trace.opaque.find("initial state"), std::string::npos) << varied << trace.opaque;
  }
  ReadTrace trace;
  trace.watched = {"mu"};  // its sign is checked, nothing else
  read_model_string(tether, "tether.yaml", {}, &trace);
  EXPECT_TRUE(trace.opaque.empty()) << trace.opaque;
  EXPECT_EQ(trace.checks.size(), 1u);
}

}  // namespace
}  // namespace lagrange::sweep
