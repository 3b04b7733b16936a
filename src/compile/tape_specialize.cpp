// Tape::specialize: constant folding on the tape itself (docs/theory.md §8: linear in tape size,
// instead of GiNaC subs on the expression DAG).

#include <fmt/format.h>

#include <stdexcept>

#include "compile/tape_builder.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

Tape Tape::specialize(size_t first, const std::vector<double>& values) const {
  using tape_detail::Op;
  using tape_detail::Term;
  if (first > num_inputs_ || values.size() > num_inputs_ - first) {
    throw std::invalid_argument(
        fmt::format("specialize: inputs [{}, {}) expected within the tape's {} inputs", first,
                    first + values.size(), num_inputs_));
  }
  // Replay every instruction through the folding builder; `val` maps each register to the SSA
  // value it currently holds (registers are reused, so it is updated as the replay proceeds).
  tape_detail::TapeBuilder b(num_inputs_);
  std::vector<std::uint32_t> val(num_registers_, 0);
  std::vector<std::uint32_t> factors;
  std::vector<Term> terms;
  for (const Instr& ins : code_) {
    std::uint32_t v = 0;
    switch (ins.op) {
      case Op::Const:
        v = b.constant(ins.c);
        break;
      case Op::Input:
        v = ins.a >= first && ins.a - first < values.size() ? b.constant(values[ins.a - first])
                                                            : b.input(ins.a);
        break;
      case Op::Sum:
        terms.clear();
        for (std::uint32_t i = 0; i < ins.b; ++i) {
          terms.push_back({coeffs_[ins.a + i], {val[args_[ins.a + i]]}});
        }
        v = b.sum(terms, ins.c);
        break;
      case Op::SumProd: {
        terms.clear();
        std::uint32_t p = ins.a;
        for (std::uint32_t t = 0; t < ins.b; ++t) {
          Term term{coeffs_[p], {}};
          for (std::uint32_t j = 1; j <= args_[p]; ++j) term.factors.push_back(val[args_[p + j]]);
          p += args_[p] + 1;
          terms.push_back(std::move(term));
        }
        v = b.sum(terms, ins.c);
        break;
      }
      case Op::Prod:
        factors.clear();
        for (std::uint32_t i = 0; i < ins.b; ++i) factors.push_back(val[args_[ins.a + i]]);
        v = b.prod(ins.c, factors);
        break;
      case Op::PowInt:
        v = b.pow_int(val[ins.a], static_cast<int>(ins.c));
        break;
      case Op::Div:
      case Op::Pow:
      case Op::Atan2:
        v = b.binary(ins.op, val[ins.a], val[ins.b]);
        break;
      default:
        v = b.unary(ins.op, val[ins.a]);
        break;
    }
    val[ins.dst] = v;
  }
  std::vector<std::uint32_t> out;
  out.reserve(outputs_.size());
  for (std::uint32_t o : outputs_) out.push_back(val[o]);
  return from_code(b.finish(out));
}

}  // namespace lagrange
