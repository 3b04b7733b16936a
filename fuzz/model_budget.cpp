#include "model_budget.hpp"

#include <cmath>

namespace lagrange::fuzz {
namespace {

// Walks the expressions of a model, counting nodes and rejecting large powers and numbers.
class Meter {
 public:
  explicit Meter(const Budget& budget) : budget_(budget) {}

  void add(const GiNaC::ex& e) {
    for (auto it = e.preorder_begin(); it != e.preorder_end() && ok_; ++it) {
      if (++nodes_ > budget_.max_nodes) ok_ = false;
      if (GiNaC::is_a<GiNaC::numeric>(*it)) check_number(GiNaC::ex_to<GiNaC::numeric>(*it));
      if (GiNaC::is_a<GiNaC::power>(*it)) {
        const GiNaC::ex exponent = it->op(1);
        if (!GiNaC::is_a<GiNaC::numeric>(exponent) ||
            std::abs(GiNaC::ex_to<GiNaC::numeric>(exponent).to_double()) > budget_.max_exponent)
          ok_ = false;
      }
    }
  }
  void add(const Vec3& v) {
    for (const auto& c : v) add(c);
  }
  bool ok() const { return ok_; }

 private:
  void check_number(const GiNaC::numeric& x) {
    if (!x.is_real() || !x.is_rational()) {
      const double d = std::abs(GiNaC::real(x).to_double()) + std::abs(GiNaC::imag(x).to_double());
      if (!(d <= budget_.max_number)) ok_ = false;
      return;
    }
    const double num = std::abs(x.numer().to_double()), den = std::abs(x.denom().to_double());
    if (!(num <= budget_.max_number) || !(den <= budget_.max_number)) ok_ = false;
  }

  const Budget& budget_;
  size_t nodes_ = 0;
  bool ok_ = true;
};

}  // namespace

bool fits(const Model& model, const Budget& budget) {
  if (model.coordinates.size() > budget.max_coordinates) return false;
  Meter meter(budget);
  for (const auto& in : model.inputs) meter.add(in.expr);
  for (const auto& p : model.points) meter.add(p.pos);
  meter.add(model.kinetic);
  meter.add(model.potential);
  for (const auto& q : model.generalized_forces) meter.add(q);
  for (const auto& p : model.particles) meter.add(p.mass);
  if (model.gravity) meter.add(*model.gravity);
  for (const auto& f : model.forces) meter.add(f.force);
  for (const auto& s : model.springs) {
    meter.add(s.k);
    meter.add(s.l0);
  }
  for (const auto& d : model.dampers) meter.add(d.c);
  for (const auto& c : model.constraints) meter.add(c.expr);
  for (const auto& o : model.outputs) meter.add(o.expr);
  return meter.ok();
}

}  // namespace lagrange::fuzz
