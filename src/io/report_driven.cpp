// Driven guides of the report's 3-D view (docs/model-language.md, "How a model looks"): the curve a
// driven point can move on at one instant is its position with the drive held and its one
// coordinate swept over a turn, sampled here as expressions of t, the inputs and the parameters.

#include "io/report_driven.hpp"

namespace lagrange::io {

DrivenGuides driven_guides(const Model& model, const std::vector<const Point*>& points,
                           const std::vector<GiNaC::symbol>& q) {
  DrivenGuides g;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& pos = points[i]->pos;
    auto has = [&](const GiNaC::symbol& s) {
      return pos[0].has(s) || pos[1].has(s) || pos[2].has(s);
    };
    bool driven = has(model.t);
    for (const Input& in : model.inputs) driven = driven || has(in.u) || has(in.ud) || has(in.udd);
    const GiNaC::symbol* angle = nullptr;
    size_t count = 0;
    for (const GiNaC::symbol& s : q)
      if (has(s)) angle = &s, ++count;
    if (!driven || count != 1) continue;
    g.point.push_back(i);
    for (size_t k = 0; k <= DrivenGuides::kSamples; ++k) {
      const GiNaC::ex value = 2 * GiNaC::Pi * GiNaC::numeric(static_cast<long>(k)) /
                              GiNaC::numeric(static_cast<long>(DrivenGuides::kSamples));
      for (const GiNaC::ex& c : pos) g.outputs.push_back(c.subs(*angle == value));
    }
  }
  return g;
}

}  // namespace lagrange::io
