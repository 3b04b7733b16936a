// Tape::eval: the switch-dispatch interpreter (docs/theory.md §8: ~2–3 ns per instruction).

#include "compile/tape_code.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

void Tape::eval(const double* in, double* out, double* r) const {
  using tape_detail::Op;
  const std::uint32_t* args = args_.data();
  const double* coeffs = coeffs_.data();
  for (const Instr& ins : code_) {
    double v;
    switch (ins.op) {
      case Op::Const:
        v = ins.c;
        break;
      case Op::Input:
        v = in[ins.a];
        break;
      case Op::Sum: {
        // v = Σᵢ cᵢ·r[aᵢ] (+ c), left to right.
        const std::uint32_t* a = args + ins.a;
        const double* c = coeffs + ins.a;
        v = c[0] * r[a[0]];
        for (std::uint32_t i = 1; i < ins.b; ++i) v += c[i] * r[a[i]];
        if (ins.c != 0.0) v += ins.c;
        break;
      }
      case Op::SumProd: {
        // v = Σ_terms coef·r[f₁]·…·r[f_k] (+ c), each product and the sum left to right.
        const std::uint32_t* a = args + ins.a;
        const double* c = coeffs + ins.a;
        v = 0.0;
        for (std::uint32_t t = 0; t < ins.b; ++t) {
          const std::uint32_t k = a[0];
          double p = c[0] * r[a[1]];
          for (std::uint32_t j = 2; j <= k; ++j) p *= r[a[j]];
          v = t == 0 ? p : v + p;
          a += k + 1;
          c += k + 1;
        }
        if (ins.c != 0.0) v += ins.c;
        break;
      }
      case Op::Prod: {
        const std::uint32_t* a = args + ins.a;
        v = ins.c * r[a[0]];
        for (std::uint32_t i = 1; i < ins.b; ++i) v *= r[a[i]];
        break;
      }
      case Op::Neg:
        v = -r[ins.a];
        break;
      case Op::Inv:
        v = 1.0 / r[ins.a];
        break;
      case Op::Div:
        v = r[ins.a] / r[ins.b];
        break;
      case Op::PowInt:
        v = tape_detail::pow_int(r[ins.a], static_cast<int>(ins.c));
        break;
      case Op::Pow:
        v = std::pow(r[ins.a], r[ins.b]);
        break;
      case Op::Sqrt:
        v = std::sqrt(r[ins.a]);
        break;
      case Op::Sin:
        v = std::sin(r[ins.a]);
        break;
      case Op::Cos:
        v = std::cos(r[ins.a]);
        break;
      case Op::Tan:
        v = std::tan(r[ins.a]);
        break;
      case Op::Asin:
        v = std::asin(r[ins.a]);
        break;
      case Op::Acos:
        v = std::acos(r[ins.a]);
        break;
      case Op::Atan:
        v = std::atan(r[ins.a]);
        break;
      case Op::Atan2:
        v = std::atan2(r[ins.a], r[ins.b]);
        break;
      case Op::Sinh:
        v = std::sinh(r[ins.a]);
        break;
      case Op::Cosh:
        v = std::cosh(r[ins.a]);
        break;
      case Op::Tanh:
        v = std::tanh(r[ins.a]);
        break;
      case Op::Exp:
        v = std::exp(r[ins.a]);
        break;
      case Op::Log:
        v = std::log(r[ins.a]);
        break;
      case Op::Abs:
        v = std::fabs(r[ins.a]);
        break;
      default:
        v = 0.0;
        break;
    }
    r[ins.dst] = v;
  }
  for (size_t i = 0; i < outputs_.size(); ++i) out[i] = r[outputs_[i]];
}

}  // namespace lagrange
