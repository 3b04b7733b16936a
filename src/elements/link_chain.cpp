// Lowering a joint chain (docs/theory.md §4.8): each link's frame is its parent's frame times the
// joint's origin transform times the joint motion; links with mass become posed bodies, movable
// joints coordinates, joint torques and damping generalised forces.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "elements/links.hpp"
#include "lagrange/rigid_body.hpp"
#include "model/expression_algebra.hpp"
#include "model/model_reader.hpp"
#include "model/size_limits.hpp"

namespace lagrange::elements {

namespace {

using model::mat_t_vec;
using model::ModelReader;

const Mat3 kIdentity{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};

/// A link frame in the world. Chains of joints about one coordinate axis with plain origins
/// (planar arms) keep a single angle, so that R = rot_z(q1 + q2) rather than a product.
struct Frame {
  Vec3 r{0, 0, 0};
  Mat3 R = kIdentity;
  bool identity = true;
  std::optional<size_t> spin_axis;
  GiNaC::ex spin_angle = 0;
  /// Body-frame angular velocity, composed recursively: ω = R_relᵀ ω_parent + k q̇ (§4.8). Kept
  /// nested, it is far smaller than U(RᵀṘ) expanded from a product of rotations.
  Vec3 w{0, 0, 0};
};

Vec3 add(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

/// The joint axis normalised exactly (k / |k|), or an error at the joint when it is zero.
Vec3 unit_axis(const ModelReader& r, const JointSpec& j) {
  double n2 = 0;
  for (const GiNaC::ex& c : j.axis) {
    const auto v = r.evaluate(c);
    if (!v)
      throw ModelError(j.axis_loc, fmt::format("expected the axis of joint '{}' as numbers or "
                                               "expressions of parameters",
                                               j.name));
    n2 += *v * *v;
  }
  if (!(n2 > 0) || !std::isfinite(n2))
    throw ModelError(j.axis_loc,
                     fmt::format("expected a non-zero axis for joint '{}', got [0, 0, 0]", j.name));
  const GiNaC::ex len = GiNaC::pow(
      j.axis[0] * j.axis[0] + j.axis[1] * j.axis[1] + j.axis[2] * j.axis[2], GiNaC::numeric(1, 2));
  return {j.axis[0] / len, j.axis[1] / len, j.axis[2] / len};
}

/// ±1 when k is ±e_axis, else 0.
int along(const Vec3& k, size_t axis) {
  const size_t a = (axis + 1) % 3, b = (axis + 2) % 3;
  if (!k[a].is_zero() || !k[b].is_zero()) return 0;
  if ((k[axis] - 1).is_zero()) return 1;
  if ((k[axis] + 1).is_zero()) return -1;
  return 0;
}

/// The rotation of a joint's origin (its rpy, or the matrix `dh:` gave); `plain` when there is
/// none, so that chains about one axis keep a single angle.
struct OriginRotation {
  bool plain = true;
  Mat3 fixed = kIdentity;
};
OriginRotation origin_rotation(const JointSpec& j) {
  const bool plain = !j.rotation && j.rpy[0].is_zero() && j.rpy[1].is_zero() && j.rpy[2].is_zero();
  return {plain, plain ? kIdentity : (j.rotation ? *j.rotation : rpy_rotation(j.rpy))};
}

Frame child_frame(const Frame& p, const JointSpec& j, const Vec3& k, const GiNaC::ex& q,
                  const GiNaC::ex& qd) {
  const auto [plain, fixed] = origin_rotation(j);
  Frame f;
  f.w = plain ? p.w : mat_t_vec(fixed, p.w);
  if (j.type == JointSpec::Type::Revolute) {
    f.w = mat_t_vec(axis_angle_rotation(k, q), f.w);
    for (size_t i = 0; i < 3; ++i) f.w[i] += k[i] * qd;
  }
  f.r = add(p.r, p.identity ? j.xyz : mat_vec(p.R, j.xyz));
  f.R = plain ? p.R : mat_mul(p.R, fixed);
  if (plain) {
    f.identity = p.identity;
    f.spin_axis = p.spin_axis;
    f.spin_angle = p.spin_angle;
  } else {
    f.identity = false;
  }
  if (j.type == JointSpec::Type::Prismatic) {
    const Vec3 d = mat_vec(f.R, k);
    f.r = add(f.r, {d[0] * q, d[1] * q, d[2] * q});
  } else if (j.type == JointSpec::Type::Revolute) {
    for (size_t axis = 0; axis < 3; ++axis) {
      const int sign = along(k, axis);
      if (sign == 0 || !(f.identity || f.spin_axis == axis)) continue;
      f.spin_angle = f.identity ? sign * q : f.spin_angle + sign * q;
      f.spin_axis = axis;
      f.identity = false;
      f.R = model::axis_rotation(axis, f.spin_angle);
      return f;
    }
    f.R = mat_mul(f.R, axis_angle_rotation(k, q));
    f.identity = false;
    f.spin_axis.reset();
  }
  return f;
}

const char* type_word(JointSpec::Type t) {
  switch (t) {
    case JointSpec::Type::Revolute:
      return "revolute";
    case JointSpec::Type::Prismatic:
      return "prismatic";
    case JointSpec::Type::Fixed:
      return "fixed";
  }
  return "fixed";
}

/// The link's frame in its parent's frame (docs/theory.md §4.9): R = R_fixed Rot(k, q) for a
/// revolute joint, origin xyz + R_fixed k q for a prismatic one.
TreeJoint tree_joint(const JointSpec& j, const Vec3& k, const GiNaC::ex& q, int parent,
                     int coordinate) {
  TreeJoint t;
  t.parent = parent;
  t.coordinate = coordinate;
  t.axis = k;
  t.origin = j.xyz;
  const auto [plain, fixed] = origin_rotation(j);
  t.rotation = fixed;
  switch (j.type) {
    case JointSpec::Type::Revolute:
      t.kind = TreeJoint::Kind::Revolute;
      t.rotation = plain ? axis_angle_rotation(k, q) : mat_mul(fixed, axis_angle_rotation(k, q));
      break;
    case JointSpec::Type::Prismatic:
      t.kind = TreeJoint::Kind::Prismatic;
      t.origin = add(j.xyz, mat_vec(fixed, {k[0] * q, k[1] * q, k[2] * q}));
      break;
    case JointSpec::Type::Fixed:
      t.kind = TreeJoint::Kind::Fixed;
      break;
  }
  return t;
}

}  // namespace

void declare_chain(ModelReader& r, LinkChain& chain) {
  // The size limit before any frame is composed: a chain's frames are products of all the
  // rotations above them, so 10 000 links would take minutes to reach the limit one by one.
  size_t coordinates = r.model().coordinates.size();
  for (const LinkSpec& link : chain.links)
    if (link.joint.type != JointSpec::Type::Fixed && ++coordinates > model::kMaxCoordinates)
      throw ModelError(
          link.joint.loc,
          fmt::format("expected at most {} coordinates in the model (written and "
                      "generated together), got more: {} has {} movable joints",
                      model::kMaxCoordinates, chain.title,
                      std::count_if(chain.links.begin(), chain.links.end(), [](const LinkSpec& l) {
                        return l.joint.type != JointSpec::Type::Fixed;
                      })));
  std::vector<Frame> frames;
  chain.coordinate.assign(chain.links.size(), -1);
  const int first = static_cast<int>(r.model().tree.size());
  for (size_t i = 0; i < chain.links.size(); ++i) {
    const LinkSpec& link = chain.links[i];
    const JointSpec& j = link.joint;
    const Frame& parent = link.parent < 0 ? Frame{} : frames.at(static_cast<size_t>(link.parent));
    GiNaC::ex q = 0, qd = 0;
    Vec3 k = j.axis;
    if (j.type != JointSpec::Type::Fixed) {
      k = unit_axis(r, j);
      const Coordinate& c = r.add_named_coordinate(j.name, j.initial, j.rate, j.loc);
      q = c.q;
      qd = c.v;
      chain.coordinate[i] = static_cast<int>(r.model().coordinates.size() - 1);
    }
    frames.push_back(child_frame(parent, j, k, q, qd));
    const Frame& f = frames.back();
    if (!link.mass.is_zero()) {
      Body b;
      b.name = link.name;
      b.mass = link.mass;
      b.inertia = link.inertia;
      b.com = link.com;
      b.position = f.r;
      b.rotation = f.R;
      b.angular_velocity = f.w;
      b.loc = link.inertia_loc;
      r.check_inertia(b, f.spin_axis);
      b.loc = link.loc;
      r.add_body(b);
    }
    TreeJoint t =
        tree_joint(j, k, q, link.parent < 0 ? -1 : first + link.parent, chain.coordinate[i]);
    if (!link.mass.is_zero()) t.body = static_cast<int>(r.model().bodies.size() - 1);
    r.model().tree.push_back(std::move(t));
    for (const auto& [name, p] : link.points)
      r.add_point(link.name + "." + name, add(f.r, mat_vec(f.R, p)), link.loc);
  }
}

// A joint torque τ (force for a prismatic joint) does virtual work τ δq on its own coordinate
// (docs/theory.md §4.2); viscous damping adds −b q̇.
void lower_chain(ModelReader& r, const LinkChain& chain) {
  Model& m = r.model();
  ElementSummary summary{chain.title, {}, {}};
  for (size_t i = 0; i < chain.links.size(); ++i) {
    const LinkSpec& link = chain.links[i];
    const JointSpec& j = link.joint;
    const std::string parent =
        link.parent < 0 ? "world" : chain.links[static_cast<size_t>(link.parent)].name;
    if (chain.coordinate[i] < 0) {
      summary.notes.push_back(fmt::format("link {}: fixed to {}{}", link.name, parent,
                                          link.mass.is_zero() ? ", massless" : ""));
      continue;
    }
    const Coordinate& c = m.coordinates[static_cast<size_t>(chain.coordinate[i])];
    summary.notes.push_back(
        fmt::format("link {}: {} joint {} on {}", link.name, type_word(j.type), c.name, parent));
    GiNaC::ex tau = j.torque.value_or(GiNaC::ex(0));
    const GiNaC::ex q_force = tau - j.damping * c.v;
    if (!q_force.is_zero()) {
      m.generalized_forces[static_cast<size_t>(chain.coordinate[i])] += q_force;
      summary.equations.emplace_back("Q_" + c.name, q_force);
    }
  }
  m.element_summaries.push_back(std::move(summary));
}

}  // namespace lagrange::elements
