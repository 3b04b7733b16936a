#include "compile/tape_builder.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace lagrange::tape_detail {

namespace {

/// Appends the bytes of `v` to `key`.
template <class T>
void append_bytes(std::string& key, const T& v) {
  char buf[sizeof(T)];
  std::memcpy(buf, &v, sizeof(T));
  key.append(buf, sizeof(T));
}

}  // namespace

std::uint32_t TapeBuilder::emit(Instr ins, const std::vector<std::uint32_t>& args,
                                const std::vector<double>& coeffs) {
  const bool has_list = ins.op == Op::Sum || ins.op == Op::Prod || ins.op == Op::SumProd;
  std::string key;
  key.reserve(24 + 12 * args.size());
  append_bytes(key, ins.op);
  if (!has_list) append_bytes(key, ins.a);
  append_bytes(key, ins.b);
  append_bytes(key, ins.c);
  for (std::uint32_t a : args) append_bytes(key, a);
  for (double c : coeffs) append_bytes(key, c);
  auto [it, inserted] = numbering_.try_emplace(std::move(key), 0);
  if (!inserted) return it->second;
  if (has_list) {
    ins.a = static_cast<std::uint32_t>(args_.size());
    args_.insert(args_.end(), args.begin(), args.end());
    coeffs_.insert(coeffs_.end(), coeffs.begin(), coeffs.end());
  }
  ins.dst = static_cast<std::uint32_t>(code_.size());
  code_.push_back(ins);
  it->second = ins.dst;
  return ins.dst;
}

std::uint32_t TapeBuilder::constant(double v) {
  return emit({Op::Const, 0, 0, 0, v}, {}, {});
}

std::uint32_t TapeBuilder::input(std::uint32_t index) {
  return emit({Op::Input, 0, index, 0, 0.0}, {}, {});
}

std::uint32_t TapeBuilder::unary(Op op, std::uint32_t x) {
  if (is_constant(x)) return constant(apply_unary(op, value(x)));
  return emit({op, 0, x, 0, 0.0}, {}, {});
}

std::uint32_t TapeBuilder::binary(Op op, std::uint32_t x, std::uint32_t y) {
  if (is_constant(x) && is_constant(y)) return constant(apply_binary(op, value(x), value(y)));
  return emit({op, 0, x, y, 0.0}, {}, {});
}

std::uint32_t TapeBuilder::pow_int(std::uint32_t x, int n) {
  if (n == 1) return x;
  if (is_constant(x)) return constant(tape_detail::pow_int(value(x), n));
  if (n == -1) return unary(Op::Inv, x);
  return emit({Op::PowInt, 0, x, 0, static_cast<double>(n)}, {}, {});
}

std::uint32_t TapeBuilder::prod(double coef, const std::vector<std::uint32_t>& factors) {
  std::vector<std::uint32_t> kept;
  kept.reserve(factors.size());
  for (std::uint32_t f : factors) {
    if (is_constant(f)) {
      coef *= value(f);
    } else {
      kept.push_back(f);
    }
  }
  if (kept.empty() || coef == 0.0) return constant(kept.empty() ? coef : 0.0);
  if (kept.size() == 1 && coef == 1.0) return kept[0];
  if (kept.size() == 1 && coef == -1.0) return unary(Op::Neg, kept[0]);
  const auto n = static_cast<std::uint32_t>(kept.size());
  return emit({Op::Prod, 0, 0, n, coef}, kept, std::vector<double>(kept.size(), 0.0));
}

std::uint32_t TapeBuilder::sum(const std::vector<Term>& terms, double constant_term) {
  std::vector<Term> kept;
  kept.reserve(terms.size());
  bool all_single = true;
  for (const Term& t : terms) {
    Term k{t.coef, {}};
    for (std::uint32_t f : t.factors) {
      if (is_constant(f)) {
        k.coef *= value(f);
      } else {
        k.factors.push_back(f);
      }
    }
    if (k.coef == 0.0) continue;
    if (k.factors.empty()) {
      constant_term += k.coef;
      continue;
    }
    all_single = all_single && k.factors.size() == 1;
    kept.push_back(std::move(k));
  }
  if (kept.empty()) return constant(constant_term);
  if (kept.size() == 1 && constant_term == 0.0) return prod(kept[0].coef, kept[0].factors);
  std::vector<std::uint32_t> args;
  std::vector<double> coeffs;
  for (const Term& t : kept) {
    if (!all_single) {
      args.push_back(static_cast<std::uint32_t>(t.factors.size()));
      coeffs.push_back(t.coef);
    }
    for (std::uint32_t f : t.factors) {
      args.push_back(f);
      coeffs.push_back(all_single ? t.coef : 0.0);
    }
  }
  const auto n = static_cast<std::uint32_t>(kept.size());
  return emit({all_single ? Op::Sum : Op::SumProd, 0, 0, n, constant_term}, args, coeffs);
}

TapeCode TapeBuilder::finish(const std::vector<std::uint32_t>& outputs) const {
  constexpr std::uint32_t kForever = std::numeric_limits<std::uint32_t>::max();
  const size_t n = code_.size();
  // Liveness and last reader of every value, by one backward sweep.
  std::vector<std::uint32_t> last(n, 0);
  std::vector<char> live(n, 0);
  for (std::uint32_t o : outputs) {
    live[o] = 1;
    last[o] = kForever;
  }
  for (size_t v = n; v-- > 0;) {
    if (!live[v]) continue;
    for_each_operand(code_[v], args_, [&](std::uint32_t u) {
      live[u] = 1;
      last[u] = std::max(last[u], static_cast<std::uint32_t>(v));
    });
  }
  // Forward sweep: free an operand's register at its last reader, then allocate the result.
  TapeCode out;
  out.num_inputs = num_inputs_;
  std::vector<std::uint32_t> reg(n, kForever);
  std::vector<std::uint32_t> free_list;
  for (size_t v = 0; v < n; ++v) {
    if (!live[v]) continue;
    Instr ins = code_[v];
    for_each_operand(ins, args_, [&](std::uint32_t u) {
      if (last[u] == v && reg[u] != kForever) {
        free_list.push_back(reg[u]);
        last[u] = kForever - 1;  // freed once even if read twice here
      }
    });
    const auto remap = [&](std::uint32_t u) { return reg[u]; };
    if (is_unary(ins.op)) {
      ins.a = remap(ins.a);
    } else if (is_binary(ins.op)) {
      ins.a = remap(ins.a);
      ins.b = remap(ins.b);
    } else if (ins.op == Op::Sum || ins.op == Op::Prod || ins.op == Op::SumProd) {
      const auto start = static_cast<std::uint32_t>(out.args.size());
      std::uint32_t len = ins.b;
      if (ins.op == Op::SumProd) {
        len = 0;
        for (std::uint32_t t = 0; t < ins.b; ++t) len += args_[ins.a + len] + 1;
      }
      for (std::uint32_t i = 0; i < len; ++i) {
        out.args.push_back(args_[ins.a + i]);
        out.coeffs.push_back(coeffs_[ins.a + i]);
      }
      std::uint32_t p = start;
      for (std::uint32_t t = 0; t < (ins.op == Op::SumProd ? ins.b : 0); ++t) {
        const std::uint32_t k = out.args[p];
        for (std::uint32_t j = 1; j <= k; ++j) out.args[p + j] = remap(out.args[p + j]);
        p += k + 1;
      }
      if (ins.op != Op::SumProd) {
        for (std::uint32_t i = 0; i < len; ++i) out.args[start + i] = remap(out.args[start + i]);
      }
      ins.a = start;
    }
    if (free_list.empty()) {
      ins.dst = static_cast<std::uint32_t>(out.num_registers++);
    } else {
      ins.dst = free_list.back();
      free_list.pop_back();
    }
    reg[v] = ins.dst;
    out.code.push_back(ins);
  }
  out.outputs.reserve(outputs.size());
  for (std::uint32_t o : outputs) out.outputs.push_back(reg[o]);
  return out;
}

}  // namespace lagrange::tape_detail
