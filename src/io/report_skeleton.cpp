// The kinematic skeleton of the report's 3-D view (docs/model-language.md, "How a model looks"): a
// link's frame is its body's pose, or for a massless link its parent's frame times the joint's
// transform (docs/theory.md §4.9, Joints: r = r_parent + R_parent p, R = R_parent R_joint); bones
// join a joint to its children's joints, a leaf link's joint to its centre of mass and points, and
// the world's base to the root joints.

#include "io/report_skeleton.hpp"

#include <algorithm>
#include <string>

#include "model/vec3_algebra.hpp"

namespace lagrange::io {

namespace {

using GiNaC::ex;
using model::add;
using model::mat_mul;
using model::mat_vec;

struct Frame {
  Vec3 r{0, 0, 0};
  Mat3 R{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
};

/// The range [lo, hi] of a coordinate's column over the run, widened to hold 0 (where the rail
/// meets its parent).
std::pair<double, double> travel(const Trajectory& traj, const std::string& column) {
  const auto it = std::find(traj.columns.begin(), traj.columns.end(), column);
  double lo = 0, hi = 0;
  if (it == traj.columns.end()) return {lo, hi};
  const size_t c = static_cast<size_t>(it - traj.columns.begin());
  for (size_t r = 0; r < traj.rows(); ++r) {
    const double x = traj.data[r * traj.columns.size() + c];
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  }
  return {lo, hi};
}

}  // namespace

Skeleton skeleton(const Model& model, const Trajectory& traj) {
  Skeleton s;
  if (model.tree.empty()) return s;
  nlohmann::json nodes = nlohmann::json::array(), bones = nlohmann::json::array();
  nlohmann::json rails = nlohmann::json::array(), axes = nlohmann::json::array();
  std::vector<ex> axis_outputs;
  auto node = [&](const std::string& name, const char* kind, const Vec3& at) {
    nodes.push_back({{"name", name}, {"kind", kind}});
    s.outputs.insert(s.outputs.end(), at.begin(), at.end());
    return nodes.size() - 1;
  };
  const size_t base = node("world", "base", Vec3{0, 0, 0});

  const size_t n = model.tree.size();
  std::vector<Frame> frames(n);
  std::vector<size_t> joint_node(n);
  std::vector<bool> has_child(n, false);
  for (const TreeJoint& j : model.tree)
    if (j.parent >= 0) has_child[static_cast<size_t>(j.parent)] = true;
  for (size_t i = 0; i < n; ++i) {
    const TreeJoint& j = model.tree[i];
    const Frame parent = j.parent < 0 ? Frame{} : frames[static_cast<size_t>(j.parent)];
    const size_t parent_node = j.parent < 0 ? base : joint_node[static_cast<size_t>(j.parent)];
    const Body* body = j.body >= 0 ? &model.bodies[static_cast<size_t>(j.body)] : nullptr;
    if (body) {
      frames[i] = {body->origin(), body->rot()};
    } else {
      frames[i].r = add(parent.r, mat_vec(parent.R, j.origin));
      frames[i].R = mat_mul(parent.R, j.rotation);
    }
    const Coordinate* c =
        j.coordinate >= 0 ? &model.coordinates[static_cast<size_t>(j.coordinate)] : nullptr;
    const std::string name = body ? body->name : (c ? c->name : "joint " + std::to_string(i + 1));
    joint_node[i] = node(name, "joint", frames[i].r);
    if (j.kind == TreeJoint::Kind::Prismatic && c) {
      // The rail is fixed in the parent's frame: where the link is for each value of q.
      auto on_rail = [&](double q) {
        Vec3 o;
        for (size_t k = 0; k < 3; ++k) o[k] = j.origin[k].subs(c->q == q);
        return add(parent.r, mat_vec(parent.R, o));
      };
      const auto [lo, hi] = travel(traj, c->name);
      const size_t anchor = node(name, "anchor", on_rail(0));
      bones.push_back({parent_node, anchor});
      rails.push_back({node(name, "rail", on_rail(lo)), node(name, "rail", on_rail(hi))});
    } else {
      bones.push_back({parent_node, joint_node[i]});
    }
    if (j.kind != TreeJoint::Kind::Fixed && c) {
      axes.push_back({{"node", joint_node[i]},
                      {"kind", j.kind == TreeJoint::Kind::Prismatic ? "prismatic" : "revolute"},
                      {"name", c->name}});
      const Vec3 a = mat_vec(frames[i].R, j.axis);
      axis_outputs.insert(axis_outputs.end(), a.begin(), a.end());
    }
    // A leaf link ends at its centre of mass and at its own points (`<link>.<point>`).
    if (!has_child[i] && body) {
      if (!(body->com[0].is_zero() && body->com[1].is_zero() && body->com[2].is_zero()))
        bones.push_back({joint_node[i], node(name, "com", body->world_point(body->com))});
      const std::string prefix = body->name + ".";
      for (const Point& p : model.points)
        if (p.name.compare(0, prefix.size(), prefix) == 0)
          bones.push_back({joint_node[i], node(p.name, "point", p.pos)});
    }
  }
  s.nodes = nodes.size();
  s.axes = axes.size();
  s.outputs.insert(s.outputs.end(), axis_outputs.begin(), axis_outputs.end());
  s.layout = {{"nodes", nodes}, {"bones", bones}, {"rails", rails}, {"axes", axes}};
  return s;
}

}  // namespace lagrange::io
