// CanonicalOrder and Tape::compile do not depend on GiNaC's hash order (issue 8, item 10): the
// same expressions built from symbols created at another time give the same keys and tapes.

#include "compile/canonical_order.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "compile/pendulum_expressions.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace {

using GiNaC::ex;
using GiNaC::symbol;
using tape_detail::CanonicalOrder;

/// a·sin(b) + 3·b²·c − c/a + a·b·c, from symbols created in the order given by `names`.
ex sample(const std::vector<std::string>& names) {
  std::map<std::string, symbol> s;
  for (const auto& n : names) s.emplace(n, symbol(n));
  const ex a = s.at("a"), b = s.at("b"), c = s.at("c");
  return a * sin(b) + 3 * pow(b, 2) * c - c / a + a * b * c;
}

TEST(CanonicalOrder, KeysDependOnStructureAndNamesOnly) {
  CanonicalOrder order;
  const ex x = sample({"a", "b", "c"}), y = sample({"c", "b", "a"});
  EXPECT_EQ(order.key(x), order.key(y));
  EXPECT_EQ(order.compare(x, y), 0);
  EXPECT_NE(order.key(x), order.key(x + 1));
  EXPECT_NE(order.compare(x, x + 1), 0);
  EXPECT_EQ(order.compare(x, x + 1), -order.compare(x + 1, x));
}

TEST(CanonicalOrder, PairOrderIsTheSameForEitherSymbolOrder) {
  CanonicalOrder order;
  const ex x = sample({"a", "b", "c"}), y = sample({"c", "b", "a"});
  const auto& px = tape_detail::PairAccess::pairs(GiNaC::ex_to<GiNaC::expairseq>(x));
  const auto& py = tape_detail::PairAccess::pairs(GiNaC::ex_to<GiNaC::expairseq>(y));
  const std::vector<std::uint32_t> ox = order.pair_order(x), oy = order.pair_order(y);
  ASSERT_EQ(ox.size(), oy.size());
  for (size_t i = 0; i < ox.size(); ++i) {
    EXPECT_EQ(order.compare(px[ox[i]].rest, py[oy[i]].rest), 0) << i;
    EXPECT_EQ(order.compare(px[ox[i]].coeff, py[oy[i]].coeff), 0) << i;
  }
}

TEST(CanonicalOrder, TapeIsTheSameWhenSymbolsAreCreatedLater) {
  const test::Pendulum first = test::make_pendulum(6);
  std::vector<symbol> unrelated;  // shift the serial numbers of everything created next
  for (int i = 0; i < 37; ++i) unrelated.emplace_back("u" + std::to_string(i));
  const test::Pendulum second = test::make_pendulum(6);
  const std::string a = Tape::compile(first.outputs, first.inputs).to_c("f");
  const std::string b = Tape::compile(second.outputs, second.inputs).to_c("f");
  EXPECT_TRUE(a == b) << "first:\n" << a << "\nsecond:\n" << b;
}

// GiNaC makes a sum inside a product "unit normal" by its first term in hash order, so with
// symbols created at other times it holds (a − b)·c or −(b − a)·c; the tape must not notice.
TEST(CanonicalOrder, SignGinacGivesASumInsideAProductDoesNotReachTheTape) {
  std::string first;
  std::set<std::string> ginac_forms;
  for (int round = 0; round < 24; ++round) {
    const symbol a("a"), b("b"), c("c"), d("d");
    const std::vector<ex> outputs = {(a - b) * c * d, sin((a - b) * c), pow(a - b, 3) * c,
                                     sqrt(a - b) * c + (b - a) * d, 1 / (a - b) + d};
    std::ostringstream printed;
    for (const ex& e : outputs) printed << e << ';';
    ginac_forms.insert(printed.str());
    const Tape t = Tape::compile(outputs, {a, b, c, d});
    const std::vector<double> at = {0.3, 0.2, -0.7, 2.5};
    std::vector<double> out(outputs.size()), work(t.work_size());
    t.eval(at.data(), out.data(), work.data());
    const GiNaC::exmap point = {{a, at[0]}, {b, at[1]}, {c, at[2]}, {d, at[3]}};
    for (size_t i = 0; i < outputs.size(); ++i) {
      const double want = GiNaC::ex_to<GiNaC::numeric>(outputs[i].subs(point).evalf()).to_double();
      EXPECT_NEAR(out[i], want, 1e-13 * std::abs(want)) << outputs[i];
    }
    const std::string tape = t.to_c("f");
    if (round == 0) first = tape;
    EXPECT_TRUE(tape == first) << "round " << round << ":\n" << tape << "\nround 0:\n" << first;
  }
  // The test means something only if GiNaC's form did change between rounds.
  EXPECT_GT(ginac_forms.size(), 1u);
}

}  // namespace
}  // namespace lagrange
