#include "compile/collect_factors.hpp"

#include <unordered_map>
#include <utility>

#include "compile/canonical_order.hpp"
#include "compile/ginac_util.hpp"

namespace lagrange {

namespace {

using GiNaC::ex;
using tape_detail::ExMap;
using tape_detail::PairAccess;

/// A product with one of its factors left out: the remainder X of a term a·X. Compared by
/// the remaining (base, exponent) pairs, which GiNaC keeps in canonical order, so no GiNaC
/// object is built to find equal remainders.
struct Remainder {
  const GiNaC::epvector* pairs;
  size_t skip;
};

/// Hash of a Remainder from the cached hashes of its pairs.
struct RemainderHash {
  size_t operator()(const Remainder& r) const {
    size_t h = r.pairs->size();
    for (size_t j = 0; j < r.pairs->size(); ++j) {
      if (j == r.skip) continue;
      const GiNaC::expair& p = (*r.pairs)[j];
      h = h * 1000003u ^ (p.rest.gethash() * 31u + p.coeff.gethash());
    }
    return h;
  }
};

/// Structural equality of two Remainders.
struct RemainderEqual {
  bool operator()(const Remainder& a, const Remainder& b) const {
    if (a.pairs->size() != b.pairs->size()) return false;
    for (size_t i = 0, j = 0;; ++i, ++j) {
      if (i == a.skip) ++i;
      if (j == b.skip) ++j;
      if (i >= a.pairs->size() || j >= b.pairs->size()) return true;
      if (!(*a.pairs)[i].is_equal((*b.pairs)[j])) return false;
    }
  }
};

/// The GiNaC expression of a Remainder.
ex to_ex(const Remainder& r) {
  GiNaC::exvector factors;
  factors.reserve(r.pairs->size());
  for (size_t j = 0; j < r.pairs->size(); ++j) {
    const GiNaC::expair& p = (*r.pairs)[j];
    if (j != r.skip) factors.push_back(pow(p.rest, p.coeff));
  }
  return ex(GiNaC::dynallocate<GiNaC::mul>(std::move(factors)));
}

/// Bottom-up rewriter with a memo so that shared subexpressions are rewritten once.
class FactorCollector : public GiNaC::map_function {
 public:
  /// A rewriter that visits terms and factors in `order`.
  explicit FactorCollector(tape_detail::CanonicalOrder& order) : order_(order) {}

  /// The rewritten form of e.
  ex operator()(const ex& e) override {
    if (e.nops() == 0) return e;
    if (auto it = memo_.find(e); it != memo_.end()) return it->second;
    ex r = GiNaC::is_a<GiNaC::expairseq>(e) ? rewrite_pairs(e) : e.map(*this);
    if (GiNaC::is_a<GiNaC::add>(r)) r = group_sum(GiNaC::ex_to<GiNaC::add>(r));
    memo_.emplace(e, r);
    return r;
  }

 private:
  /// e (an add or mul) with each pair's rest rewritten; e itself when nothing changed. Works
  /// on the pairs directly instead of GiNaC's map, which allocates a recombined term per pair.
  ex rewrite_pairs(const ex& e) {
    const bool is_sum = GiNaC::is_a<GiNaC::add>(e);
    const auto& s = GiNaC::ex_to<GiNaC::expairseq>(e);
    const GiNaC::epvector& pairs = PairAccess::pairs(s);
    GiNaC::exvector rests;
    rests.reserve(pairs.size());
    bool changed = false;
    for (const GiNaC::expair& p : pairs) {
      rests.push_back((*this)(p.rest));
      changed = changed || !GiNaC::are_ex_trivially_equal(rests.back(), p.rest);
    }
    if (!changed) return e;
    GiNaC::exvector parts;
    parts.reserve(pairs.size() + 1);
    for (size_t i = 0; i < pairs.size(); ++i) {
      parts.push_back(is_sum ? rests[i] * pairs[i].coeff : pow(rests[i], pairs[i].coeff));
    }
    parts.push_back(PairAccess::overall(s));
    if (is_sum) return ex(GiNaC::dynallocate<GiNaC::add>(std::move(parts)));
    return ex(GiNaC::dynallocate<GiNaC::mul>(std::move(parts)));
  }

  /// Σ cᵢ·aᵢ·X + rest → X·Σ cᵢ·aᵢ + rest (docs/theory.md §8): each term a·X, a a plain symbol
  /// factor, joins the remainder X shared by the most terms; single-member groups stay as
  /// they were. Terms and factors are visited in canonical order, so that ties between
  /// remainders are broken the same way in every process (GiNaC's order is not).
  /// Cost: O(terms · factors²) hashing, GiNaC objects only for rewritten groups.
  ex group_sum(const GiNaC::add& s) {
    const GiNaC::epvector& pairs = PairAccess::pairs(s);
    const std::vector<std::uint32_t> terms_in_order = order_.pair_order(s);
    std::vector<std::vector<Remainder>> cand(pairs.size());
    std::unordered_map<Remainder, size_t, RemainderHash, RemainderEqual> count;
    for (size_t i : terms_in_order) {
      if (!GiNaC::is_a<GiNaC::mul>(pairs[i].rest)) continue;
      const GiNaC::epvector& f = PairAccess::pairs(GiNaC::ex_to<GiNaC::mul>(pairs[i].rest));
      for (size_t j : order_.pair_order(pairs[i].rest)) {
        if (GiNaC::is_a<GiNaC::symbol>(f[j].rest) &&
            GiNaC::ex_to<GiNaC::numeric>(f[j].coeff).is_equal(1)) {
          cand[i].push_back({&f, j});
          ++count[cand[i].back()];
        }
      }
    }
    // Each term's best remainder; group members in first-seen order.
    std::vector<int> choice(pairs.size(), -1);
    std::unordered_map<Remainder, size_t, RemainderHash, RemainderEqual> group_of;
    std::vector<std::vector<size_t>> groups;
    for (size_t i : terms_in_order) {
      size_t best = 1;
      for (size_t j = 0; j < cand[i].size(); ++j) {
        const size_t n = count[cand[i][j]];
        if (n > best) {
          best = n;
          choice[i] = static_cast<int>(j);
        }
      }
      if (choice[i] < 0) continue;
      auto [it, fresh] = group_of.try_emplace(cand[i][choice[i]], groups.size());
      if (fresh) groups.emplace_back();
      groups[it->second].push_back(i);
    }
    bool any = false;
    for (const auto& g : groups) any = any || g.size() > 1;
    if (!any) return s;
    GiNaC::exvector terms;
    terms.reserve(pairs.size() + 1);
    std::vector<char> done(pairs.size(), 0);
    for (const auto& g : groups) {
      if (g.size() < 2) continue;
      GiNaC::exvector inner;
      inner.reserve(g.size());
      for (size_t i : g) {
        const Remainder& r = cand[i][choice[i]];
        inner.push_back((*r.pairs)[r.skip].rest * pairs[i].coeff);
        done[i] = 1;
      }
      const ex x = to_ex(cand[g[0]][choice[g[0]]]);
      terms.push_back(x * ex(GiNaC::dynallocate<GiNaC::add>(std::move(inner))));
    }
    for (size_t i = 0; i < pairs.size(); ++i) {
      if (!done[i]) terms.push_back(pairs[i].rest * pairs[i].coeff);
    }
    terms.push_back(PairAccess::overall(s));
    return ex(GiNaC::dynallocate<GiNaC::add>(std::move(terms)));
  }

  tape_detail::CanonicalOrder& order_;
  ExMap<ex> memo_;
};

}  // namespace

GiNaC::ex collect_common_factors(const GiNaC::ex& e) {
  tape_detail::CanonicalOrder order;
  FactorCollector f(order);
  return f(e);
}

std::vector<GiNaC::ex> collect_common_factors(const std::vector<GiNaC::ex>& es,
                                              tape_detail::CanonicalOrder& order) {
  FactorCollector f(order);
  std::vector<GiNaC::ex> out;
  out.reserve(es.size());
  for (const GiNaC::ex& e : es) out.push_back(f(e));
  return out;
}

}  // namespace lagrange
