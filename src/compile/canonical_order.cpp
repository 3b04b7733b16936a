#include "compile/canonical_order.hpp"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <typeinfo>

namespace lagrange::tape_detail {

namespace {

using GiNaC::ex;
using GiNaC::numeric;

/// Node kinds, the first level of the order.
enum class Kind : std::uint8_t { Numeric, Symbol, Constant, Add, Mul, Power, Function, Other };

Kind kind_of(const ex& e) {
  // Pointer comparison of type_info first: std::type_info's operator== compares names with
  // strcmp whenever the objects differ, and this runs once per node of large DAGs.
  const std::type_info& t = typeid(GiNaC::ex_to<GiNaC::basic>(e));
  if (&t == &typeid(GiNaC::symbol)) return Kind::Symbol;
  if (&t == &typeid(numeric)) return Kind::Numeric;
  if (&t == &typeid(GiNaC::mul)) return Kind::Mul;
  if (&t == &typeid(GiNaC::add)) return Kind::Add;
  if (&t == &typeid(GiNaC::power)) return Kind::Power;
  if (GiNaC::is_exactly_a<numeric>(e)) return Kind::Numeric;
  if (GiNaC::is_a<GiNaC::symbol>(e)) return Kind::Symbol;
  if (GiNaC::is_exactly_a<GiNaC::constant>(e)) return Kind::Constant;
  if (GiNaC::is_exactly_a<GiNaC::add>(e)) return Kind::Add;
  if (GiNaC::is_exactly_a<GiNaC::mul>(e)) return Kind::Mul;
  if (GiNaC::is_exactly_a<GiNaC::power>(e)) return Kind::Power;
  if (GiNaC::is_exactly_a<GiNaC::function>(e)) return Kind::Function;
  return Kind::Other;
}

/// splitmix64's finaliser: a well-mixed 64-bit value of x.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15u;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9u;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebu;
  return x ^ (x >> 31);
}

/// h extended by v (order-sensitive).
std::uint64_t combine(std::uint64_t h, std::uint64_t v) {
  return mix(h ^ (v + 0x9e3779b97f4a7c15u + (h << 6) + (h >> 2)));
}

/// FNV-1a of a string: the same value in every process and on every platform.
std::uint64_t text_hash(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325u;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3u;
  return h;
}

/// The bits of v (+0 for −0).
std::uint64_t double_bits(double v) {
  if (v == 0.0) v = 0.0;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

/// −1 for a negative real number, else +1.
int sign_of(const numeric& n) {
  return n.is_negative() ? -1 : 1;
}

/// s·n for s = ±1.
numeric times(const numeric& n, int s) {
  return s < 0 ? n.mul(numeric(-1)) : n;
}

/// Hash of the value s·n, rounded to double (exact equality is left to the comparison).
std::uint64_t numeric_hash(const numeric& n, int s = 1) {
  if (n.is_real()) return combine(double_bits(s * n.to_double()), 0);
  return combine(double_bits(s * n.real().to_double()), double_bits(s * n.imag().to_double()));
}

/// True when e is an integer number (a power of it keeps or flips the sign of its base).
bool is_integer(const ex& e) {
  return GiNaC::is_exactly_a<numeric>(e) && GiNaC::ex_to<numeric>(e).is_integer();
}

/// The sign an integer exponent n gives to a base of sign s.
int power_sign(int s, const ex& n) {
  return s < 0 && GiNaC::ex_to<numeric>(n).is_odd() ? -1 : 1;
}

/// The name that identifies a node of kind Constant, Function or Other (beyond its operands).
std::string name_of(const ex& e, Kind k) {
  if (k == Kind::Constant) {
    std::ostringstream s;
    s << e;
    return s.str();
  }
  if (k == Kind::Function) return GiNaC::ex_to<GiNaC::function>(e).get_name();
  return GiNaC::ex_to<GiNaC::basic>(e).class_name();
}

template <class T>
int three_way(const T& a, const T& b) {
  return a < b ? -1 : (b < a ? 1 : 0);
}

}  // namespace

CanonicalOrder::CanonicalOrder(const std::vector<GiNaC::symbol>& inputs) {
  for (size_t i = 0; i < inputs.size(); ++i)
    input_index_.emplace(inputs[i], static_cast<std::uint32_t>(i));
}

CanonicalOrder::Entry& CanonicalOrder::entry(const ex& e) {
  const GiNaC::basic* node = &GiNaC::ex_to<GiNaC::basic>(e);
  if (auto it = memo_.find(node); it != memo_.end()) return it->second;
  const Kind k = kind_of(e);
  Entry en{e, 0, 1, static_cast<std::uint8_t>(k), kNoId, {}};
  std::uint64_t h = mix(static_cast<std::uint64_t>(k));
  switch (k) {
    case Kind::Numeric:
      h = combine(h, numeric_hash(GiNaC::ex_to<numeric>(e)));
      break;
    case Kind::Symbol:
      if (auto it = input_index_.find(e); it != input_index_.end()) {
        h = combine(h, it->second);
      } else {
        h = combine(combine(h, 0xffffffffu), text_hash(GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
      }
      break;
    case Kind::Add:
    case Kind::Mul:
      fill_pairs(en, k == Kind::Add);
      h = combine(h, en.key);
      break;
    case Kind::Power:  // b^n = sign(b)^n·R(b)^n for an integer n; otherwise the sign of b stays
      if (is_integer(e.op(1))) {
        h = combine(combine(h, key(e.op(0))), key(e.op(1)));
        en.sign = power_sign(sign(e.op(0)), e.op(1));
      } else {
        h = combine(combine(h, signed_key(e.op(0))), signed_key(e.op(1)));
      }
      break;
    default:
      h = combine(h, text_hash(name_of(e, k)));
      for (size_t i = 0; i < e.nops(); ++i) h = combine(h, signed_key(e.op(i)));
      break;
  }
  en.key = h;
  return memo_.emplace(node, std::move(en)).first->second;
}

void CanonicalOrder::fill_pairs(Entry& en, bool is_sum) {
  const auto& s = GiNaC::ex_to<GiNaC::expairseq>(en.e);
  const GiNaC::epvector& pairs = PairAccess::pairs(s);
  const numeric& overall = GiNaC::ex_to<numeric>(PairAccess::overall(s));
  // Each rest's entry once; sort keys that do not depend on the signs GiNaC chose: canonical
  // rest and |coefficient| of a term; canonical rest and exponent of a factor (and the base's
  // sign unless the exponent is an integer).
  const size_t n = pairs.size();
  std::vector<std::uint64_t> rest_key(n), sort_key(n);
  std::vector<int> rest_sign(n);
  for (size_t i = 0; i < n; ++i) {
    const Entry& r = entry(pairs[i].rest);
    rest_key[i] = r.key;
    rest_sign[i] = r.sign;
    const numeric& c = GiNaC::ex_to<numeric>(pairs[i].coeff);
    if (is_sum) {
      sort_key[i] = combine(r.key, numeric_hash(c, sign_of(c)));
    } else {
      const std::uint64_t base = is_integer(c) ? 0 : static_cast<std::uint64_t>(r.sign + 2);
      sort_key[i] = combine(combine(r.key, numeric_hash(c)), base);
    }
    en.order.push_back(static_cast<std::uint32_t>(i));
  }
  std::sort(en.order.begin(), en.order.end(), [&](std::uint32_t i, std::uint32_t j) {
    if (sort_key[i] != sort_key[j]) return sort_key[i] < sort_key[j];
    return compare_pairs(pairs[i], pairs[j], is_sum) < 0;
  });
  // The sign: a sum's first term gets a positive coefficient; a product's sign is that of its
  // coefficient times those of its odd integer powers.
  if (is_sum && n > 0) {
    const std::uint32_t first = en.order.front();
    en.sign = sign_of(GiNaC::ex_to<numeric>(pairs[first].coeff)) * rest_sign[first];
  } else if (!is_sum) {
    en.sign = sign_of(overall);
    for (size_t i = 0; i < n; ++i)
      if (is_integer(pairs[i].coeff)) en.sign *= power_sign(rest_sign[i], pairs[i].coeff);
  }
  std::uint64_t h = 0;
  for (std::uint32_t i : en.order) {
    if (is_sum) {  // the coefficient of R(rest) in R(sum)
      const numeric& c = GiNaC::ex_to<numeric>(pairs[i].coeff);
      h = combine(h, combine(rest_key[i], numeric_hash(c, en.sign * rest_sign[i])));
    } else {
      h = combine(h, sort_key[i]);
    }
  }
  en.key = combine(h, numeric_hash(overall, is_sum ? en.sign : sign_of(overall)));
}

std::uint32_t CanonicalOrder::id(const ex& e) {
  Entry& en = entry(e);
  if (en.id != kNoId) return en.id;
  auto& same_key = ids_[en.key];
  for (const auto& [other, id] : same_key) {
    if (compare(other, e) == 0) return en.id = id;
  }
  en.id = next_id_++;
  same_key.emplace_back(e, en.id);
  return en.id;
}

std::uint64_t CanonicalOrder::signed_key(const ex& e) {
  const Entry& en = entry(e);
  return combine(en.key, static_cast<std::uint64_t>(en.sign + 2));
}

int CanonicalOrder::compare_signed(const ex& a, const ex& b) {
  if (const int c = three_way(sign(a), sign(b)); c != 0) return c;
  return compare(a, b);
}

int CanonicalOrder::compare_pairs(const GiNaC::expair& p, const GiNaC::expair& q, bool is_sum) {
  if (const int c = compare(p.rest, q.rest); c != 0) return c;
  const numeric& a = GiNaC::ex_to<numeric>(p.coeff);
  const numeric& b = GiNaC::ex_to<numeric>(q.coeff);
  if (is_sum) {
    if (const int c = abs(a).compare(abs(b)); c != 0) return c;
    return three_way(sign_of(a) * sign(p.rest), sign_of(b) * sign(q.rest));
  }
  if (const int c = a.compare(b); c != 0) return c;
  return is_integer(a) ? 0 : three_way(sign(p.rest), sign(q.rest));
}

int CanonicalOrder::compare_sequences(const ex& a, const ex& b, bool is_sum) {
  const auto& sa = GiNaC::ex_to<GiNaC::expairseq>(a);
  const auto& sb = GiNaC::ex_to<GiNaC::expairseq>(b);
  const GiNaC::epvector& pa = PairAccess::pairs(sa);
  const GiNaC::epvector& pb = PairAccess::pairs(sb);
  if (const int c = three_way(pa.size(), pb.size()); c != 0) return c;
  const std::vector<std::uint32_t>& oa = pair_order(a);
  const std::vector<std::uint32_t>& ob = pair_order(b);
  const int ga = sign(a), gb = sign(b);
  for (size_t i = 0; i < oa.size(); ++i) {
    const GiNaC::expair& p = pa[oa[i]];
    const GiNaC::expair& q = pb[ob[i]];
    if (const int c = compare(p.rest, q.rest); c != 0) return c;
    const numeric& x = GiNaC::ex_to<numeric>(p.coeff);
    const numeric& y = GiNaC::ex_to<numeric>(q.coeff);
    if (is_sum) {  // coefficients of the canonical rests in the canonical sums
      if (const int c = times(x, ga * sign(p.rest)).compare(times(y, gb * sign(q.rest))); c != 0)
        return c;
    } else {
      if (const int c = x.compare(y); c != 0) return c;
      if (!is_integer(x)) {
        if (const int c = three_way(sign(p.rest), sign(q.rest)); c != 0) return c;
      }
    }
  }
  const numeric& ka = GiNaC::ex_to<numeric>(PairAccess::overall(sa));
  const numeric& kb = GiNaC::ex_to<numeric>(PairAccess::overall(sb));
  if (is_sum) return times(ka, ga).compare(times(kb, gb));
  return abs(ka).compare(abs(kb));
}

int CanonicalOrder::compare(const ex& a, const ex& b) {
  if (GiNaC::are_ex_trivially_equal(a, b)) return 0;
  if (const int c = three_way(key(a), key(b)); c != 0) return c;
  // Equal keys: almost always equal structure; compare in full so that the order is total.
  const auto k = static_cast<Kind>(entry(a).kind);
  if (const int c = three_way(entry(a).kind, entry(b).kind); c != 0) return c;
  switch (k) {
    case Kind::Numeric:
      return GiNaC::ex_to<numeric>(a).compare(GiNaC::ex_to<numeric>(b));
    case Kind::Symbol: {
      auto ia = input_index_.find(a), ib = input_index_.find(b);
      const bool in_a = ia != input_index_.end(), in_b = ib != input_index_.end();
      if (in_a != in_b) return in_a ? -1 : 1;
      if (in_a) return three_way(ia->second, ib->second);
      return GiNaC::ex_to<GiNaC::symbol>(a).get_name().compare(
          GiNaC::ex_to<GiNaC::symbol>(b).get_name());
    }
    case Kind::Add:
    case Kind::Mul:
      return compare_sequences(a, b, k == Kind::Add);
    case Kind::Power: {
      if (const int c = compare_signed(a.op(1), b.op(1)); c != 0) return c;
      return is_integer(a.op(1)) ? compare(a.op(0), b.op(0)) : compare_signed(a.op(0), b.op(0));
    }
    default: {
      if (const int c = name_of(a, k).compare(name_of(b, k)); c != 0) return c;
      if (const int c = three_way(a.nops(), b.nops()); c != 0) return c;
      for (size_t i = 0; i < a.nops(); ++i)
        if (const int c = compare_signed(a.op(i), b.op(i)); c != 0) return c;
      return 0;
    }
  }
}

}  // namespace lagrange::tape_detail
