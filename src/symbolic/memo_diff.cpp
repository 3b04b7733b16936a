#include "symbolic/memo_diff.hpp"

#include <algorithm>

namespace lagrange::symbolic {

MemoDiff::MemoDiff(const std::vector<GiNaC::symbol>& columns)
    : columns_(columns), memo_(columns.size()) {
  for (size_t k = 0; k < columns.size(); ++k) column_of_.emplace(columns[k], k);
}

MemoDiff::MemoDiff(const std::vector<GiNaC::symbol>& inputs, const std::vector<size_t>& columns)
    : MemoDiff([&] {
        std::vector<GiNaC::symbol> chosen;
        for (size_t c : columns) chosen.push_back(inputs.at(c));
        return chosen;
      }()) {}

const std::vector<size_t>& MemoDiff::columns_in(const GiNaC::ex& e) {
  if (const auto it = deps_.find(e); it != deps_.end()) return it->second;
  std::vector<size_t> found;
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    if (const auto c = column_of_.find(e); c != column_of_.end()) found.push_back(c->second);
  } else {
    for (size_t i = 0; i < e.nops(); ++i) {
      const std::vector<size_t>& sub = columns_in(e.op(i));
      found.insert(found.end(), sub.begin(), sub.end());
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
  }
  return deps_.emplace(e, std::move(found)).first->second;
}

GiNaC::ex MemoDiff::partial(const GiNaC::ex& f, size_t i) {
  // f(s₁…s_n) differentiated by sᵢ with fresh symbols, then the arguments put back: GiNaC's
  // own rule for the function, applied to a node of size n.
  GiNaC::exmap back;
  GiNaC::exvector args;
  std::vector<GiNaC::symbol> s(f.nops());
  for (size_t j = 0; j < f.nops(); ++j) {
    args.push_back(s[j]);
    back[s[j]] = f.op(j);
  }
  const GiNaC::function& fn = GiNaC::ex_to<GiNaC::function>(f);
  const GiNaC::ex generic = GiNaC::function(fn.get_serial(), args);
  return generic.diff(s[i]).subs(back, GiNaC::subs_options::no_pattern);
}

// Sum, product and chain rules over the DAG; a node without x_k in it has derivative 0.
GiNaC::ex MemoDiff::diff(const GiNaC::ex& e, size_t k) {
  const std::vector<size_t>& deps = columns_in(e);
  if (!std::binary_search(deps.begin(), deps.end(), k)) return 0;
  if (GiNaC::is_a<GiNaC::symbol>(e)) return 1;
  if (const auto it = memo_[k].find(e); it != memo_[k].end()) return it->second;
  GiNaC::ex d = 0;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    GiNaC::exvector terms;
    for (size_t i = 0; i < e.nops(); ++i) terms.push_back(diff(e.op(i), k));
    d = GiNaC::add(terms);
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    GiNaC::exvector terms;
    for (size_t i = 0; i < e.nops(); ++i) {
      const GiNaC::ex di = diff(e.op(i), k);
      if (di.is_zero()) continue;
      GiNaC::exvector factors{di};
      for (size_t j = 0; j < e.nops(); ++j)
        if (j != i) factors.push_back(e.op(j));
      terms.push_back(GiNaC::mul(factors));
    }
    d = GiNaC::add(terms);
  } else if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1))) {
    const GiNaC::ex& b = e.op(0);
    const GiNaC::ex& n = e.op(1);
    d = n * GiNaC::pow(b, n - 1) * diff(b, k);
  } else if (GiNaC::is_a<GiNaC::function>(e)) {
    GiNaC::exvector terms;
    for (size_t i = 0; i < e.nops(); ++i) {
      const GiNaC::ex di = diff(e.op(i), k);
      if (!di.is_zero()) terms.push_back(partial(e, i) * di);
    }
    d = GiNaC::add(terms);
  } else {
    d = e.diff(columns_[k]);  // anything else (a power with a symbolic exponent): GiNaC's rule
  }
  memo_[k].emplace(e, d);
  return d;
}

}  // namespace lagrange::symbolic
