// CanonicalOrder and Tape::compile do not depend on GiNaC's hash order (issue 8, item 10): the
// same expressions built from symbols created at another time give the same keys and tapes.

#include "compile/canonical_order.hpp"

#include <gtest/gtest.h>

#include <map>
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

}  // namespace
}  // namespace lagrange
