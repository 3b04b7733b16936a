// Tape::compile + Tape::eval against GiNaC's own evaluation, CSE and instruction counts.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compile/pendulum_expressions.hpp"
#include "compile/run_tape.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

/// GiNaC's value of e at inputs = x, evaluated with 30 digits.
double reference(const ex& e, const std::vector<symbol>& inputs, const std::vector<double>& x) {
  GiNaC::exmap m;
  for (size_t i = 0; i < inputs.size(); ++i) m[inputs[i]] = GiNaC::numeric(x[i]);
  const long saved = GiNaC::Digits;
  GiNaC::Digits = 30;
  const ex v = e.subs(m).evalf();
  GiNaC::Digits = saved;
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

/// Evaluates every output of t at x.

/// Number of instructions of t calling C function `fn` (counted in the emitted C, which has
/// one statement per instruction; the instruction list itself is private).
size_t count_calls(const Tape& t, const std::string& fn) {
  const std::string c = t.to_c("f");
  const std::string needle = "= " + fn + "(";
  size_t n = 0;
  for (size_t p = c.find(needle); p != std::string::npos; p = c.find(needle, p + 1)) ++n;
  return n;
}

TEST(TapeEval, EveryOpMatchesGinac) {
  symbol x("x"), y("y"), z("z");
  const std::vector<symbol> in = {x, y, z};
  const ex s = sin(x * y) + 1;  // shared subexpression
  const std::vector<ex> outs = {
      3 * x + 2 * y - z + 7,
      x * y * z / 5,
      -x,
      1 / (x + 3),
      (x + 1) / (y * y + 2),
      pow(x, 2) + pow(y, 3) - pow(z, -2) + pow(x + y, 5) * pow(y, -4),
      pow(x * x + 1, GiNaC::numeric(1, 2)),
      pow(y * y + 1, GiNaC::numeric(3, 2)) + pow(2 + x * x, z),
      sqrt(z * z + x * x) * s,
      sin(x) + cos(y) + tan(z / 3),
      asin(tanh(x)) + acos(sin(y) / 2) + atan(z),
      atan2(y, x) + atan2(-x, z),
      sinh(x / 2) * cosh(y / 3) - tanh(z),
      exp(x / 3) * log(1 + y * y) + abs(z - 1),
      pow(s, 3) * s - s / (2 + cos(s)),
      GiNaC::Pi * x + GiNaC::numeric(1, 3),
      pow(x, 12) + pow(y, -9),
  };
  const Tape t = Tape::compile(outs, in);
  for (unsigned seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.4, 1.4);
    const std::vector<double> point = {u(rng), u(rng), u(rng) + 3.0};
    const std::vector<double> got = run(t, point);
    for (size_t i = 0; i < outs.size(); ++i) {
      const double want = reference(outs[i], in, point);
      EXPECT_NEAR(got[i], want, 1e-14 * std::max(1.0, std::fabs(want)))
          << "output " << i << " = " << outs[i] << " at seed " << seed;
    }
  }
}

TEST(TapeEval, RandomNestedExpressionsMatchGinac) {
  symbol a("a"), b("b"), c("c"), d("d");
  const std::vector<symbol> in = {a, b, c, d};
  std::mt19937 rng(42);
  // Random trees over a pool that grows with every node built, so subtrees are shared.
  std::vector<ex> pool = {a, b, c, d, GiNaC::numeric(3, 7)};
  for (int step = 0; step < 300; ++step) {
    const ex p = pool[rng() % pool.size()], q = pool[rng() % pool.size()];
    ex e;
    switch (rng() % 8) {
      case 0:
        e = p + q;
        break;
      case 1:
        e = p * q;
        break;
      case 2:
        e = p - 2 * q;
        break;
      case 3:
        e = sin(p) * q;
        break;
      case 4:
        e = cos(p + q);
        break;
      case 5:
        e = p / (2 + q * q);
        break;
      case 6:
        e = exp(tanh(p));
        break;
      default:
        e = atan(p) + pow(q, 2);
        break;
    }
    pool.push_back(e);
  }
  const std::vector<ex> outs(pool.end() - 40, pool.end());
  const Tape t = Tape::compile(outs, in);
  const std::vector<double> point = {0.3, -0.7, 0.55, 1.1};
  const std::vector<double> got = run(t, point);
  for (size_t i = 0; i < outs.size(); ++i) {
    const double want = reference(outs[i], in, point);
    EXPECT_NEAR(got[i], want, 1e-13 * std::max(1.0, std::fabs(want))) << "output " << i;
  }
}

TEST(TapeCse, ExpressionUsedHundredTimesIsOneInstruction) {
  symbol x("x");
  std::vector<symbol> in = {x};
  std::vector<ex> outs;
  const ex s = sin(x * x + 1);
  for (int k = 0; k < 100; ++k) {
    symbol y("y" + std::to_string(k));
    in.push_back(y);
    outs.push_back(s * y + k);
  }
  const Tape t = Tape::compile(outs, in);
  EXPECT_EQ(count_calls(t, "sin"), 1u);
  // Input x, PowInt x², Sum x²+1, Sin; then per output Input yₖ and one fused s·yₖ + k.
  EXPECT_EQ(t.num_instructions(), 4u + 2u * 100u);
}

TEST(TapeCse, StructurallyEqualSubexpressionsAreShared) {
  symbol x("x"), y("y");
  const ex e1 = cos(x + y) * x;
  const ex e2 = cos(y + x) * x;  // built separately, equal structure
  const Tape t = Tape::compile({e1, e2 + 1}, {x, y});
  EXPECT_EQ(count_calls(t, "cos"), 1u);
}

TEST(TapeCse, KnownInstructionCounts) {
  symbol x("x"), y("y"), z("z");
  // sin x·cos x + sin x: Input, Sin, Cos, one fused SumProd.
  EXPECT_EQ(Tape::compile({sin(x) * cos(x) + sin(x)}, {x}).num_instructions(), 4u);
  // x·y + x·z → x·(y + z) (docs/theory.md §8): three Inputs, Sum, Prod.
  EXPECT_EQ(Tape::compile({x * y + x * z}, {x, y, z}).num_instructions(), 5u);
  // x/y: two Inputs and one Div, no separate Inv.
  EXPECT_EQ(Tape::compile({x / y}, {x, y}).num_instructions(), 3u);
  // Constants fold at compile time: sin(2)·x is Input and Prod.
  EXPECT_EQ(Tape::compile({sin(ex(2)) * x}, {x}).num_instructions(), 2u);
}

TEST(TapeCse, RegistersAreReused) {
  const test::Pendulum p = test::make_pendulum(6);
  const Tape t = Tape::compile(p.outputs, p.inputs);
  EXPECT_LT(t.work_size(), t.num_instructions());
  const std::vector<double> x = test::pendulum_point(6, 1);
  const std::vector<double> got = run(t, x);
  for (size_t i = 0; i < p.outputs.size(); ++i) {
    const double want = reference(p.outputs[i], p.inputs, x);
    EXPECT_NEAR(got[i], want, 1e-13 * std::max(1.0, std::fabs(want))) << "output " << i;
  }
}

TEST(TapeErrors, UnknownSymbolIsNamed) {
  symbol x("x"), stray("stray_length");
  try {
    Tape::compile({x + sin(stray)}, {x});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stray_length"), std::string::npos) << e.what();
  }
}

TEST(TapeErrors, UnsupportedFunctionIsNamed) {
  symbol x("x");
  try {
    Tape::compile({GiNaC::tgamma(x)}, {x});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tgamma"), std::string::npos) << e.what();
  }
}

TEST(TapeErrors, DuplicateInputIsRejected) {
  symbol x("x");
  EXPECT_THROW(Tape::compile({x}, {x, x}), std::invalid_argument);
}

TEST(TapeEval, EmptyTapeAndConstantOutputs) {
  symbol x("x");
  const Tape t = Tape::compile({ex(2), GiNaC::numeric(1, 4) * 2}, {x});
  EXPECT_EQ(t.num_outputs(), 2u);
  const std::vector<double> got = run(t, {0.0});
  EXPECT_EQ(got[0], 2.0);
  EXPECT_EQ(got[1], 0.5);
  EXPECT_EQ(Tape::compile({}, {x}).num_instructions(), 0u);
}

}  // namespace
}  // namespace lagrange
