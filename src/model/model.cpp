#include "lagrange/model.hpp"

#include <stdexcept>

namespace lagrange {

namespace {
template <class Seq>
int index_by_name(const Seq& seq, const std::string& name) {
  for (size_t i = 0; i < seq.size(); ++i)
    if (seq[i].name == name) return static_cast<int>(i);
  return -1;
}
}  // namespace

int Model::coordinate_index(const std::string& name) const {
  return index_by_name(coordinates, name);
}
int Model::parameter_index(const std::string& name) const {
  return index_by_name(parameters, name);
}
int Model::input_index(const std::string& name) const {
  return index_by_name(inputs, name);
}

const Point* Model::find_point(const std::string& name) const {
  int i = index_by_name(points, name);
  return i < 0 ? nullptr : &points[static_cast<size_t>(i)];
}

const Body* Model::find_body(const std::string& name) const {
  int i = index_by_name(bodies, name);
  return i < 0 ? nullptr : &bodies[static_cast<size_t>(i)];
}

GiNaC::ex Model::time_derivative(const GiNaC::ex& e) const {
  GiNaC::ex d = e.diff(t);
  for (const auto& c : coordinates) {
    if (e.has(c.a)) throw std::logic_error("time derivative of an acceleration is not supported");
    d += e.diff(c.q) * c.v + e.diff(c.v) * c.a;
  }
  for (const auto& b : bodies) {  // ṙ, and Ṙ = RΩ on SO(3) (docs/theory.md §4.4)
    if (!b.free) continue;
    for (size_t k = 0; k < 3; ++k) {
      if (e.has(b.rdd[k]) || e.has(b.wd[k]))
        throw std::logic_error("time derivative of a body's acceleration is not supported");
      d += e.diff(b.r[k]) * b.rd[k] + e.diff(b.rd[k]) * b.rdd[k] + e.diff(b.w[k]) * b.wd[k];
    }
    const GiNaC::ex W[3][3] = {{0, -b.w[2], b.w[1]}, {b.w[2], 0, -b.w[0]}, {-b.w[1], b.w[0], 0}};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const GiNaC::ex dR = e.diff(b.R[3 * i + j]);
        if (dR.is_zero()) continue;
        for (size_t l = 0; l < 3; ++l) d += dR * b.R[3 * i + l] * W[l][j];
      }
  }
  for (const auto& in : inputs) {
    if (e.has(in.udd))
      throw std::logic_error("time derivative of the second derivative of input '" + in.name +
                             "' is not supported");
    d += e.diff(in.u) * in.ud + e.diff(in.ud) * in.udd;
  }
  return d;
}

}  // namespace lagrange
