#pragma once
// A canonical form of GiNaC expressions that depends only on their structure (docs/theory.md §8).
// GiNaC orders the operands of sums and products by hash values seeded with load addresses and
// symbol creation order, and it makes a sum inside a product "unit normal" with respect to the
// first term in that order, so the same model gives (a − b)·c in one process and −(b − a)·c in
// another. Tapes are built from this canonical form, so they are the same in every process.

#include <ginac/ginac.h>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "compile/ginac_util.hpp"

namespace lagrange::tape_detail {

/// Every expression e is sign(e)·R(e), R(e) its canonical form: in a sum, the first term in
/// canonical order has a positive coefficient; a product keeps |its coefficient|, with the
/// signs of its own coefficient and of its integer-power factors moved out. The key of R(e)
/// is a 64-bit hash of node kinds, symbol identities (position among the tape inputs, else
/// name), numeric values and function names, with the operands of sums and products sorted;
/// equal keys fall back to a full structural comparison. Results are memoised per node (the
/// nodes are kept alive meanwhile).
class CanonicalOrder {
 public:
  /// Symbols are identified by their names.
  CanonicalOrder() = default;
  /// Symbols are identified by their position in `inputs` (names for any other symbol).
  explicit CanonicalOrder(const std::vector<GiNaC::symbol>& inputs);

  /// The structural key of R(e).
  std::uint64_t key(const GiNaC::ex& e) { return entry(e).key; }
  /// +1 or −1: e = sign(e)·R(e).
  int sign(const GiNaC::ex& e) { return entry(e).sign; }
  /// Negative, zero or positive as R(a) orders before, equals, or orders after R(b).
  int compare(const GiNaC::ex& a, const GiNaC::ex& b);
  /// The indices of the (rest, coeff) pairs of an add or mul, in canonical order.
  const std::vector<std::uint32_t>& pair_order(const GiNaC::ex& e) { return entry(e).order; }
  /// A dense number (0, 1, 2, … in order of first request) naming R(e): the same for two
  /// expressions exactly when their canonical forms are equal, whatever signs GiNaC gave them.
  std::uint32_t id(const GiNaC::ex& e);

 private:
  struct Entry {
    GiNaC::ex e;                       ///< keeps the node (and so its address) alive
    std::uint64_t key = 0;             ///< structural hash of R(e)
    int sign = 1;                      ///< e = sign·R(e)
    std::uint8_t kind = 0;             ///< node kind (numeric, symbol, add, mul, …)
    std::uint32_t id = kNoId;          ///< id() once requested
    std::vector<std::uint32_t> order;  ///< add/mul: pair indices in canonical order
  };
  static constexpr std::uint32_t kNoId = 0xffffffffu;
  /// The memoised entry of e, computed on first use.
  Entry& entry(const GiNaC::ex& e);
  /// Fills key, sign and order of an add or a mul.
  void fill_pairs(Entry& en, bool is_sum);
  /// The key of an operand whose sign is part of the structure (function arguments, bases
  /// of non-integer powers).
  std::uint64_t signed_key(const GiNaC::ex& e);
  /// compare() of operands whose sign is part of the structure.
  int compare_signed(const GiNaC::ex& a, const GiNaC::ex& b);
  /// Orders pair p of an add (is_sum) or mul before pair q: by canonical rest, then by the
  /// magnitude of the coefficient, then by the sign the pair contributes.
  int compare_pairs(const GiNaC::expair& p, const GiNaC::expair& q, bool is_sum);
  /// Deep comparison of two adds or two muls with equal keys.
  int compare_sequences(const GiNaC::ex& a, const GiNaC::ex& b, bool is_sum);

  ExMap<std::uint32_t> input_index_;
  std::unordered_map<const GiNaC::basic*, Entry> memo_;
  /// Key → (expression, id) of each canonical form with that key.
  std::unordered_map<std::uint64_t, std::vector<std::pair<GiNaC::ex, std::uint32_t>>> ids_;
  std::uint32_t next_id_ = 0;
};

}  // namespace lagrange::tape_detail
