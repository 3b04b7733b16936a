// Denavit–Hartenberg parameters in `links:` (docs/model-language.md, "Links and joints"): each
// link's joint placed from its row, standard (Spong) or modified (Craig), exactly.

#include "elements/links.hpp"
#include "model/expression_algebra.hpp"

namespace lagrange::elements {

namespace {

/// A rigid transform x ↦ t + R x.
struct Pose {
  Vec3 t{0, 0, 0};
  Mat3 R{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  bool identity = true;
};

Pose then(const Pose& a, const Pose& b) {
  if (a.identity) return b;
  if (b.identity) return a;
  const Vec3 bt = mat_vec(a.R, b.t);
  return {{a.t[0] + bt[0], a.t[1] + bt[1], a.t[2] + bt[2]}, mat_mul(a.R, b.R), false};
}

Pose rotation(size_t axis, const GiNaC::ex& angle) {
  if (angle.is_zero()) return {};
  return {{0, 0, 0}, model::axis_rotation(axis, angle), false};
}

Pose translation(size_t axis, const GiNaC::ex& length) {
  if (length.is_zero()) return {};
  Pose p;
  p.t[axis] = length;
  p.identity = false;
  return p;
}

/// Standard: R_z(θ) T_z(d) T_x(a) R_x(α), from the joint frame to the link's DH frame.
Pose standard_tail(const DhSpec& dh) {
  return then(then(rotation(2, dh.theta), translation(2, dh.d)),
              then(translation(0, dh.a), rotation(0, dh.alpha)));
}

/// Modified: R_x(α) T_x(a) R_z(θ) T_z(d), from the parent's frame to the joint frame.
Pose modified_head(const DhSpec& dh) {
  return then(then(rotation(0, dh.alpha), translation(0, dh.a)),
              then(rotation(2, dh.theta), translation(2, dh.d)));
}

bool is_identity(const Mat3& R) {
  for (size_t a = 0; a < 3; ++a)
    for (size_t b = 0; b < 3; ++b)
      if (!(R[a][b] - (a == b ? 1 : 0)).is_zero()) return false;
  return true;
}

Vec3 moved(const Pose& p, const Vec3& x) {
  if (p.identity) return x;
  const Vec3 r = mat_vec(p.R, x);
  return {p.t[0] + r[0], p.t[1] + r[1], p.t[2] + r[2]};
}

}  // namespace

// A standard-DH link's frame is its joint frame followed by R_z(θ) T_z(d) T_x(a) R_x(α): its
// children's joints (and non-DH children's origins) are placed from there, and its own mass
// properties and points, given in that frame, are moved into the joint frame.
void apply_dh(LinkChain& chain) {
  std::vector<Pose> tail(chain.links.size());  // joint frame → the frame the link is written in
  for (size_t i = 0; i < chain.links.size(); ++i) {
    LinkSpec& link = chain.links[i];
    JointSpec& j = link.joint;
    const Pose parent = link.parent < 0 ? Pose{} : tail[static_cast<size_t>(link.parent)];
    Pose origin;
    if (link.dh) {
      j.axis = {0, 0, 1};
      if (link.dh->modified)
        origin = modified_head(*link.dh);
      else
        tail[i] = standard_tail(*link.dh);
    } else {
      origin =
          then(translation(0, j.xyz[0]), then(translation(1, j.xyz[1]), translation(2, j.xyz[2])));
      if (!j.rpy[0].is_zero() || !j.rpy[1].is_zero() || !j.rpy[2].is_zero()) {
        origin.R = rpy_rotation(j.rpy);
        origin.identity = false;
      }
    }
    if (parent.identity && !link.dh) continue;  // written as URDF: nothing to do
    const Pose placed = then(parent, origin);
    j.xyz = placed.t;
    j.rpy = {0, 0, 0};
    if (!is_identity(placed.R)) j.rotation = placed.R;
    const Pose& own = tail[i];
    if (own.identity) continue;
    link.com = moved(own, link.com);
    link.inertia = mat_mul(mat_mul(own.R, link.inertia), model::transpose(own.R));
    for (auto& [name, p] : link.points) p = moved(own, p);
  }
}

}  // namespace lagrange::elements
