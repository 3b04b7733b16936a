// Numbers that once hung the readers (issue 25 items 3 and 4): URDF attributes whose exact
// decimal conversion never finished, hexadecimal and other non-decimal syntax, and the
// reciprocal of a power tower under abs(). Each run is bounded by this harness: killed after
// kLimit, and its peak memory checked.

#include <gtest/gtest.h>

#include <string>

#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

constexpr std::chrono::seconds kLimit{20};
constexpr long kMaxRssKb = 1024 * 1024;  // 1 GiB, sanitizer builds included

/// A one-joint arm whose joint origin is xyz="X 0 0" and whose mass is `mass`.
std::string arm(const std::string& x, const std::string& mass = "1") {
  return "<robot name=\"r\">\n"
         "  <link name=\"base\"/>\n"
         "  <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>\n"
         "    <origin xyz=\"" +
         x +
         " 0 0\"/><axis xyz=\"0 1 0\"/></joint>\n"
         "  <link name=\"a\"><inertial><origin xyz=\"0.3 0 0\"/><mass value=\"" +
         mass +
         "\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" "
         "izz=\"0.01\"/></inertial></link>\n"
         "</robot>\n";
}

RunResult check(const ScratchDir& dir, const std::string& file, const std::string& text) {
  spit(dir.path() / file, text);
  const RunResult r = run_lagrange(dir.path(), {"check", (dir.path() / file).string()}, kLimit);
  EXPECT_LT(r.seconds, kLimit.count()) << file << " ran until killed";
  EXPECT_LT(r.max_rss_kb, kMaxRssKb) << file;
  return r;
}

struct BadNumber {
  const char* text;
  const char* expected;  // the part of the message saying what was expected
};

TEST(UrdfNumbers, NonDecimalAndOutOfRangeNumbersAreLocatedErrors) {
  ScratchDir dir("urdf-number-bombs");
  for (const BadNumber& bad : {
           BadNumber{"1e-9999999999", "expected 0 or a number of magnitude at least"},
           BadNumber{"1e999999999999", "expected a number of magnitude at most"},
           BadNumber{"1e400", "expected a number of magnitude at most"},
           BadNumber{"+0x10", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{"0x1p3", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{"inf", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{"nan", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{"1e", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{"--1", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
           BadNumber{".", "expected a decimal number such as 0.25, -3 or 1.5e-3"},
       }) {
    SCOPED_TRACE(bad.text);
    const RunResult r = check(dir, "arm.urdf", arm(bad.text));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(std::string("arm.urdf:4: error: ") + bad.expected), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(std::string("for the origin xyz of joint 'j1', got '") + bad.text + "'"),
              std::string::npos)
        << r.err;
  }
  const RunResult mass = check(dir, "arm.urdf", arm("0", "1e-99999999999999999999"));
  EXPECT_EQ(mass.exit_code, 1) << mass.err;
  EXPECT_NE(mass.err.find("arm.urdf:5: error: expected 0 or a number of magnitude at least"),
            std::string::npos)
      << mass.err;
}

TEST(UrdfNumbers, DecimalNumbersWithLargeExponentsReadQuickly) {
  ScratchDir dir("urdf-number-ok");
  // 0 × 10^999999999999 is 0; the others are ordinary lengths written oddly.
  for (const char* text : {"0e999999999999", "-0.0e-999999999999", "+0.25", "2.5e-1", "25E-2",
                           ".25", "250000000000000000000000000000000000000000000000e-48"}) {
    SCOPED_TRACE(text);
    const RunResult r = check(dir, "arm.urdf", arm(text));
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
}

TEST(ExpressionNumbers, ReciprocalOfAPowerTowerIsBounded) {
  ScratchDir dir("reciprocal-tower");
  std::string tower = "9";
  for (int i = 1; i < 22; ++i) tower += "^9";
  const RunResult r = check(dir, "tower.yaml",
                            "coordinates:\n  x: {initial: 1}\nkinetic: der(x)^2/2\n"
                            "potential: abs(1/" +
                                tower + "^x)\n");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tower.yaml:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected powers nested at most 8 deep in their exponents"),
            std::string::npos)
      << r.err;
}

TEST(ExpressionNumbers, AbsOfAnExpTowerIsQuick) {
  // 17 levels took 3 s before abs() knew exp is positive, doubling per level; 21 take ~50 s.
  ScratchDir dir("exp-tower");
  std::string tower = "1/x";
  for (int i = 0; i < 21; ++i) tower = "exp(" + tower + ")";
  const RunResult r = check(
      dir, "tower.yaml",
      "coordinates:\n  x: {initial: 1}\nkinetic: der(x)^2/2\npotential: abs(" + tower + ")\n");
  EXPECT_LT(r.seconds, 10.0);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.exit_code << " " << r.err;
}

/// `n` coordinates q0…q(n-1) with the kinetic energy factor(q)·Σ q̇ᵢ²/2.
std::string weighted_kinetic(int n, const std::string& factor) {
  std::string y = "coordinates:\n", v;
  for (int i = 0; i < n; ++i) {
    y += "  q" + std::to_string(i) + ": {initial: 0.1}\n";
    v += (i ? " + der(q" : "der(q") + std::to_string(i) + ")^2";
  }
  return y + "kinetic: (" + factor + ")*(" + v + ")/2\npotential: 0\n";
}

/// The sum q0^p + … + q(n-1)^p.
std::string sum_of_powers(int n, int p) {
  std::string s;
  for (int i = 0; i < n; ++i)
    s += (i ? " + q" : "q") + std::to_string(i) + (p == 1 ? "" : "^" + std::to_string(p));
  return s;
}

// Derivations whose expansion blows up inside the reader's limits (issue 37 item 12): the test of
// whether T + U is a constant of motion expanded Σ q̇ ∂T/∂q̇ − 2T, which for (Σqᵢ²)²⁰ in a 459-byte
// file reached 7.9 GB in 80 s, and for a product of sums ran past 90 s. Expansions the
// derivation asks for on its own are bounded at 10 000 terms (an upper bound on the size computed
// first); beyond, that test is not made and the model is derived and checked as written.
TEST(DerivationBombs, APowerOfASumInTheKineticEnergyIsDerivedQuickly) {
  ScratchDir dir("derivation-power");
  const RunResult r =
      check(dir, "power.yaml", weighted_kinetic(6, "1 + (" + sum_of_powers(6, 2) + ")^20"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mass matrix positive definite"), std::string::npos) << r.out;
}

TEST(DerivationBombs, AProductOfSumsInTheKineticEnergyIsDerivedQuickly) {
  ScratchDir dir("derivation-product");
  std::string product;
  for (int k = 0; k < 12; ++k) product += (k ? "*(2 + " : "(2 + ") + sum_of_powers(6, 1) + ")";
  const RunResult r = check(dir, "product.yaml", weighted_kinetic(6, product));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
