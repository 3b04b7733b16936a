// The published coefficients handed to ARKODE (src/integrate/erk_coefficients.cpp), and ARKODE's
// own Fehlberg 7(8), satisfy the Runge–Kutta order conditions: every row of A sums to its node,
// and b Φ(t) = 1/γ(t) for every rooted tree t up to the nominal order (Butcher's elementary
// weights Φ and densities γ), for the propagated solution and for the embedding, and not for all
// trees one order higher. The bar 1e-11 is rounding in double (coefficients up to 120 in size
// cancel; in 50 digits the residuals are below 1e-36); the first failing order misses by more
// than 1e-8.

#include <arkode/arkode_erkstep.h>  // (its arkode_butcher_erk.h needs the stdio it includes)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "integrate/dop853_coefficients.hpp"
#include "integrate/erk_coefficients.hpp"

namespace lagrange::integration {
namespace {

/// A rooted tree: its order and its subtrees (indices of earlier trees, non-increasing).
struct Tree {
  int order;
  std::vector<size_t> children;
};

/// Every rooted tree up to max_order, each once, ordered by order.
std::vector<Tree> rooted_trees(int max_order) {
  std::vector<Tree> trees{{1, {}}};
  for (int n = 2; n <= max_order; ++n) {
    const size_t smaller = trees.size();
    std::vector<size_t> children;
    // Multisets of smaller trees whose orders sum to n − 1, as non-increasing index sequences.
    const std::function<void(int, size_t)> grow = [&](int remaining, size_t largest) {
      if (remaining == 0) {
        trees.push_back({n, children});
        return;
      }
      for (size_t i = largest + 1; i-- > 0;) {
        if (trees[i].order > remaining) continue;
        children.push_back(i);
        grow(remaining - trees[i].order, i);
        children.pop_back();
      }
    };
    grow(n - 1, smaller - 1);
  }
  return trees;
}

/// max over trees of order `order` of |w · Φ(t) − 1/γ(t)|.
double worst_residual(const ButcherCoefficients& k, const std::vector<double>& w, int order) {
  const std::vector<Tree> trees = rooted_trees(order);
  const size_t s = k.c.size();
  std::vector<std::vector<double>> phi(trees.size());  // Φ(t) per stage
  std::vector<double> gamma(trees.size());
  double worst = 0.0;
  for (size_t t = 0; t < trees.size(); ++t) {
    phi[t].assign(s, 1.0);
    gamma[t] = trees[t].order;
    for (size_t u : trees[t].children) {
      for (size_t i = 0; i < s; ++i) {
        double a_phi = 0.0;
        for (size_t j = 0; j < i; ++j) a_phi += k.a[i][j] * phi[u][j];
        phi[t][i] *= a_phi;
      }
      gamma[t] *= gamma[u];
    }
    if (trees[t].order != order) continue;
    double weight = 0.0;
    for (size_t i = 0; i < s; ++i) weight += w[i] * phi[t][i];
    worst = std::max(worst, std::abs(weight - 1.0 / gamma[t]));
  }
  return worst;
}

TEST(RootedTrees, CountsAreTheKnownOnes) {
  const std::vector<Tree> trees = rooted_trees(9);
  const int expected[] = {1, 1, 2, 4, 9, 20, 48, 115, 286};  // OEIS A000081
  for (int n = 1; n <= 9; ++n)
    EXPECT_EQ(
        std::count_if(trees.begin(), trees.end(), [&](const Tree& t) { return t.order == n; }),
        expected[n - 1])
        << "order " << n;
}

/// Row i of `a` has first_row + i entries (the stages before it), summing to c[i].
void expect_rows_sum_to_nodes(const std::vector<std::vector<double>>& a,
                              const std::vector<double>& c, size_t first_row = 0) {
  ASSERT_EQ(a.size(), c.size());
  for (size_t i = 0; i < c.size(); ++i) {
    ASSERT_EQ(a[i].size(), first_row + i) << "row " << i;
    double sum = 0.0;
    for (double x : a[i]) sum += x;
    EXPECT_NEAR(sum, c[i], 1e-14) << "row " << i;
  }
}

/// The weights w meet every order condition up to `order` (residuals below `bar`) and, with
/// `misses_by` > 0, miss some condition of order + 1 by more than that: their order is exactly
/// `order`.
void expect_order(const ButcherCoefficients& k, const std::vector<double>& w, int order, double bar,
                  double misses_by, const char* what) {
  for (int n = 1; n <= order; ++n)
    EXPECT_LT(worst_residual(k, w, n), bar) << what << ", order " << n;
  if (misses_by > 0.0) {
    EXPECT_GT(worst_residual(k, w, order + 1), misses_by)
        << what << ": order " << order + 1 << " holds too";
  }
}

TEST(Verner87, RowsOfASumToTheNodes) {
  const ButcherCoefficients& k = verner_8_7();
  ASSERT_EQ(k.c.size(), 13u);
  expect_rows_sum_to_nodes(k.a, k.c);
}

TEST(Verner87, WeightsMeetEveryOrderConditionUpToEight) {
  const ButcherCoefficients& k = verner_8_7();
  ASSERT_EQ(k.order, 8);
  expect_order(k, k.b, 8, 1e-11, 1e-8, "weights");
}

TEST(Verner87, EmbeddingMeetsEveryOrderConditionUpToSeven) {
  const ButcherCoefficients& k = verner_8_7();
  ASSERT_EQ(k.embedding, 7);
  expect_order(k, k.d, 7, 1e-11, 1e-7, "embedding (of order 8 it would estimate no error)");
}

/// ARKODE's own table `id` as coefficients (its A is stored full, s × s).
ButcherCoefficients arkode_table(ARKODE_ERKTableID id) {
  const ARKodeButcherTable t = ARKodeButcherTable_LoadERK(id);
  ButcherCoefficients k{{}, {}, {}, {}, t->q, t->p};
  for (int i = 0; i < t->stages; ++i) {
    k.c.push_back(t->c[i]);
    k.a.emplace_back(t->A[i], t->A[i] + i);
    k.b.push_back(t->b[i]);
    k.d.push_back(t->d[i]);
  }
  ARKodeButcherTable_Free(t);
  return k;
}

// SUNDIALS 6.4's ARKodeButcherTable_CheckOrder reports order 6 for this table, but it checks no
// higher order than 6: the coefficients meet every condition up to 8 (7 for the embedding).
TEST(Fehlberg78, ArkodeCoefficientsMeetEveryOrderConditionUpToEight) {
  const ButcherCoefficients k = arkode_table(ARKODE_FEHLBERG_13_7_8);
  ASSERT_EQ(k.order, 8);
  ASSERT_EQ(k.embedding, 7);
  expect_order(k, k.b, 8, 1e-13, 0.0, "weights");
  expect_order(k, k.d, 7, 1e-13, 1e-7, "embedding");
}

// DOP853: the propagated weights are of order 8, the embedding behind its first error estimate
// (b − e5) of order 5, the weights behind the second of order 3; the dense-output stages 14–16
// continue A (their rows reach back to stage 13, f at the step's end).
TEST(Dop853, CoefficientsMeetTheirOrderConditions) {
  const Dop853Coefficients& t = dop853();
  const ButcherCoefficients& k = t.main;
  ASSERT_EQ(k.c.size(), 12u);
  expect_rows_sum_to_nodes(k.a, k.c);
  expect_rows_sum_to_nodes(t.extra_a, t.extra_c, 13);
  expect_order(k, k.b, 8, 1e-12, 1e-8, "weights");
  expect_order(k, k.d, 5, 1e-12, 1e-6, "fifth-order embedding");
  expect_order(k, t.b3, 3, 1e-12, 1e-6, "third-order weights");
}

}  // namespace
}  // namespace lagrange::integration
