// The report's scene, derived from the model generically: every point (particles sized by mass,
// fixed points, points of elements such as tether nodes), every rigid body (pose and a shape from
// its declared shape or its inertia), springs and dampers, and rigid links found from the motion.
// Elements appear through the points and bodies they lower into; none is named here.

#include "io/report_scene.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "io/report_driven.hpp"
#include "io/report_skeleton.hpp"
#include "io/report_urdf.hpp"
#include "io/report_visual.hpp"

namespace lagrange::io {

namespace {

using GiNaC::ex;
using P3 = std::array<double, 3>;

/// Evaluates expressions of (t, q, v, u, p) at trajectory rows through one tape.
class RowEvaluator {
 public:
  RowEvaluator(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
               const std::vector<double>& parameters, const std::vector<ex>& outputs)
      : cm_(cm), traj_(traj), tape_(Tape::compile(outputs, eq.tape_inputs())) {
    if (parameters.size() != cm.np)
      throw std::invalid_argument(
          fmt::format("report: expected {} parameter values, got {}", cm.np, parameters.size()));
    in_.assign(cm.input_count(), 0.0);
    std::copy(parameters.begin(), parameters.end(), in_.begin() + cm.p_offset());
    t_col_ = column(traj, "t");
    for (const auto& n : cm.coordinate_names) q_cols_.push_back(column(traj, n));
    for (const auto& n : cm.velocity_names) v_cols_.push_back(column(traj, n));
    out_.resize(tape_.num_outputs());
    work_.resize(std::max(tape_.work_size(), cm.inputs.work_size()));
    u_.resize(cm.inputs.num_outputs());
  }

  const std::vector<double>& at(size_t row) {
    const size_t nc = traj_.columns.size();
    const double* r = &traj_.data[row * nc];
    in_[0] = r[t_col_];
    for (size_t i = 0; i < q_cols_.size(); ++i) in_[cm_.q_offset() + i] = r[q_cols_[i]];
    for (size_t i = 0; i < v_cols_.size(); ++i) in_[cm_.v_offset() + i] = r[v_cols_[i]];
    if (cm_.k > 0) {
      cm_.inputs.eval(in_.data(), u_.data(), work_.data());
      std::copy(u_.begin(), u_.end(), in_.begin() + cm_.u_offset());
    }
    tape_.eval(in_.data(), out_.data(), work_.data());
    return out_;
  }

 private:
  static size_t column(const Trajectory& traj, const std::string& name) {
    const auto it = std::find(traj.columns.begin(), traj.columns.end(), name);
    if (it == traj.columns.end())
      throw std::runtime_error(fmt::format(
          "the trajectory has no column '{}' of the model (a CSV of another model?)", name));
    return static_cast<size_t>(it - traj.columns.begin());
  }
  const CompiledModel& cm_;
  const Trajectory& traj_;
  Tape tape_;
  size_t t_col_ = 0;
  std::vector<size_t> q_cols_, v_cols_;
  std::vector<double> in_, out_, work_, u_;
};

/// The part of each component that depends on no coordinate, input or t: where a point is
/// attached to the ground (the pivot of `[d + a cos(th), a sin(th), 0]` is [d, 0, 0]).
Vec3 ground_part(const Vec3& pos, const std::set<ex, GiNaC::ex_is_less>& moving) {
  auto depends = [&](const ex& e) {
    for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it) && moving.count(*it)) return true;
    return false;
  };
  Vec3 base{0, 0, 0};
  for (size_t k = 0; k < 3; ++k) {
    if (!depends(pos[k])) {
      base[k] = pos[k];
    } else if (GiNaC::is_a<GiNaC::add>(pos[k])) {
      for (size_t i = 0; i < pos[k].nops(); ++i)
        if (!depends(pos[k].op(i))) base[k] += pos[k].op(i);
    }
  }
  return base;
}

double dist(const P3& a, const P3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

struct BodyShape {
  std::string kind = "box";
  P3 size{0, 0, 0};  ///< box edges, or (radius, radius, length) of a cylinder, or the sphere's
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< shape axes in body axes (columns)
};

// A body's shape from its inertia: the box (or the declared cylinder or sphere) with the same
// principal moments, along the principal axes. An inertia no solid has (a planar link's
// [0, 0, I_zz]) is drawn as a capsule from the body origin (its joint) through the centre of
// mass to twice as far.
BodyShape shape_from_inertia(const std::string& declared, double mass, const Eigen::Matrix3d& I,
                             const Eigen::Vector3d& com, double fallback) {
  BodyShape s;
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
  const bool solid = moments[2] <= moments[0] + moments[1] + 1e-9 * moments[2];
  if (!solid && declared.empty() && com.norm() > 0) {
    const Eigen::Vector3d w = com.normalized();
    Eigen::Vector3d u = std::abs(w.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    u = (u - u.dot(w) * w).normalized();
    s.kind = "capsule";
    s.axes << u, w.cross(u), w;
    const double length = 2 * com.norm();
    s.size = {0.06 * length, 0.06 * length, length};
    return s;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  Eigen::Vector3d m = eig.eigenvalues();
  s.axes = eig.eigenvectors();
  if (s.axes.determinant() < 0) s.axes.col(2) *= -1;
  if (declared == "cylinder" || declared == "sphere")
    s.axes = Eigen::Matrix3d::Identity(), m = I.diagonal();
  auto root = [](double x) { return x > 0 && std::isfinite(x) ? std::sqrt(x) : 0.0; };
  if (mass > 0 && declared == "sphere") {
    const double r = root(2.5 * m[0] / mass);
    s.kind = "sphere";
    s.size = {r, r, r};
  } else if (mass > 0 && declared == "cylinder") {
    const double r = root(2 * m[2] / mass);
    s.kind = "cylinder";
    s.size = {r, r, root(12 * m[0] / mass - 3 * r * r)};
  } else if (mass > 0) {
    for (int k = 0; k < 3; ++k)
      s.size[k] = root(6 * (m[(k + 1) % 3] + m[(k + 2) % 3] - m[k]) / mass);
  }
  const double largest = std::max({s.size[0], s.size[1], s.size[2]});
  for (double& x : s.size)
    x = largest > 0 ? std::max(x, 0.03 * largest) : fallback;  // a thin rod still shows
  return s;
}

}  // namespace

nlohmann::json scene(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                     const std::vector<double>& parameters, const ReportLimits& limits) {
  const Model& model = *eq.model;
  const Visual& visual = model.visual;
  std::set<ex, GiNaC::ex_is_less> moving(eq.kin.q.begin(), eq.kin.q.end());
  moving.insert(model.t);
  for (const auto& in : model.inputs) moving.insert({in.u, in.ud, in.udd});

  // Tape outputs: points, anchors, body poses, then (constant) gravity, masses and inertias.
  std::vector<const Point*> points;
  for (const auto& p : model.points)
    if (!visual_listed(visual.hide, p.name)) points.push_back(&p);
  std::vector<const Body*> bodies;
  for (const auto& b : model.bodies)
    if (!visual_listed(visual.hide, b.name)) bodies.push_back(&b);
  std::vector<ex> outs;
  for (const Point* p : points) outs.insert(outs.end(), p->pos.begin(), p->pos.end());
  for (const Point* p : points) {
    const Vec3 g = ground_part(p->pos, moving);
    outs.insert(outs.end(), g.begin(), g.end());
  }
  for (const Body* b : bodies) {
    const Vec3 o = b->origin();
    outs.insert(outs.end(), o.begin(), o.end());
    for (const Vec3& row : b->rot()) outs.insert(outs.end(), row.begin(), row.end());
  }
  const Skeleton bones = skeleton(model, traj);
  const size_t skeleton_at = outs.size();
  outs.insert(outs.end(), bones.outputs.begin(), bones.outputs.end());
  const DrivenGuides guides = driven_guides(model, points, eq.kin.q);
  const size_t guides_at = outs.size();
  outs.insert(outs.end(), guides.outputs.begin(), guides.outputs.end());
  const size_t static_at = outs.size();
  const Vec3 gravity = model.gravity.value_or(Vec3{0, 0, 0});
  outs.insert(outs.end(), gravity.begin(), gravity.end());
  for (const Body* b : bodies) {
    outs.push_back(b->mass);
    for (const Vec3& row : b->inertia) outs.insert(outs.end(), row.begin(), row.end());
    outs.insert(outs.end(), b->com.begin(), b->com.end());
  }
  std::map<std::string, ex> particle_mass;
  for (const auto& pa : model.particles) particle_mass[pa.point] += pa.mass;
  std::vector<std::string> massive;
  for (const auto& [name, mass] : particle_mass) {
    massive.push_back(name);
    outs.push_back(mass);
  }
  RowEvaluator eval(eq, cm, traj, parameters, outs);

  const size_t np = points.size(), nb = bodies.size();
  const size_t per_frame =
      std::max<size_t>(1, 3 * np + 12 * nb + bones.outputs.size() + guides.outputs.size());
  const std::vector<size_t> rows = sample_rows(
      traj.rows(),
      std::min(limits.max_frames, std::max<size_t>(2, limits.max_scene_numbers / per_frame)));
  const size_t nf = rows.size();
  if (nf == 0) throw std::runtime_error("the trajectory has no samples to show");
  std::vector<std::vector<P3>> pos(nf, std::vector<P3>(np));
  std::vector<std::vector<std::array<double, 12>>> pose(nf,
                                                        std::vector<std::array<double, 12>>(nb));
  std::vector<P3> ground(np);
  std::vector<double> statics;
  std::vector<std::vector<double>> joints(nf);  // skeleton: node positions, then joint axes
  std::vector<std::vector<double>> curves(nf);  // driven guides, kSamples + 1 points each
  for (size_t f = 0; f < nf; ++f) {
    const std::vector<double>& o = eval.at(rows[f]);
    joints[f].assign(o.begin() + skeleton_at, o.begin() + guides_at);
    curves[f].assign(o.begin() + guides_at, o.begin() + static_at);
    for (size_t i = 0; i < np; ++i)
      for (size_t k = 0; k < 3; ++k) pos[f][i][k] = o[3 * i + k];
    for (size_t j = 0; j < nb; ++j)
      for (size_t k = 0; k < 12; ++k) pose[f][j][k] = o[6 * np + 12 * j + k];
    if (f == 0) {
      for (size_t i = 0; i < np; ++i)
        for (size_t k = 0; k < 3; ++k) ground[i][k] = o[3 * np + 3 * i + k];
      statics.assign(o.begin() + static_at, o.end());
    }
  }

  // A driven guide is drawn when its angle closes the curve over a turn (a hoop, not a line).
  constexpr size_t kRing = DrivenGuides::kSamples;
  std::vector<size_t> rings;  // indices into guides.point
  for (size_t r = 0; r < guides.point.size(); ++r) {
    const double* c = &curves[0][3 * (kRing + 1) * r];
    double size = 0, gap = 0;
    for (size_t k = 0; k <= kRing; ++k)
      for (size_t d = 0; d < 3; ++d) size = std::max(size, std::abs(c[3 * k + d] - c[d]));
    for (size_t d = 0; d < 3; ++d) gap = std::max(gap, std::abs(c[3 * kRing + d] - c[d]));
    if (size > 0 && std::isfinite(size) && gap <= 1e-9 * size) rings.push_back(r);
  }

  // Size of the scene: the box around everything that is drawn.
  P3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  auto grow = [&](const double* x) {
    for (size_t k = 0; k < 3; ++k)
      if (std::isfinite(x[k])) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  };
  for (size_t f = 0; f < nf; ++f) {
    for (const auto& p : pos[f]) grow(p.data());
    for (const auto& b : pose[f]) grow(b.data());
    for (size_t k = 0; k < bones.nodes; ++k) grow(&joints[f][3 * k]);
    for (size_t r : rings)
      for (size_t k = 0; k < kRing; ++k) grow(&curves[f][3 * ((kRing + 1) * r + k)]);
  }
  double extent = hi[0] >= lo[0] ? dist(lo, hi) : 0.0;
  if (!(extent > 1e-9)) extent = 1.0;

  // Anchors: ground parts that some moving point keeps a constant distance to.
  std::vector<P3> anchors;
  auto find_fixed = [&](const P3& g) -> long {
    for (size_t i = 0; i < np; ++i) {
      bool fixed = true;
      for (size_t f = 0; f < nf && fixed; ++f) fixed = dist(pos[f][i], g) < 1e-9 * extent;
      if (fixed) return static_cast<long>(i);
    }
    for (size_t a = 0; a < anchors.size(); ++a)
      if (dist(anchors[a], g) < 1e-9 * extent) return static_cast<long>(np + a);
    return -1;
  };
  std::vector<long> ground_of(np, -1);
  for (size_t i = 0; i < np; ++i) {
    bool still = true;
    for (size_t f = 0; f < nf && still; ++f) still = dist(pos[f][i], pos[0][i]) < 1e-6 * extent;
    if (still) continue;
    ground_of[i] = find_fixed(ground[i]);
    if (ground_of[i] < 0) {
      anchors.push_back(ground[i]);
      ground_of[i] = static_cast<long>(np + anchors.size() - 1);
    }
  }
  std::vector<std::vector<P3>> all = pos;
  for (auto& frame : all) frame.insert(frame.end(), anchors.begin(), anchors.end());

  // Segments: springs and dampers as declared, then rigid links from the motion.
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < np; ++i) index[points[i]->name] = i;
  nlohmann::json segments = nlohmann::json::array();
  std::vector<std::pair<size_t, size_t>> declared;
  auto add_declared = [&](const std::string& a, const std::string& b, const char* kind) {
    if (!index.count(a) || !index.count(b)) return;
    declared.emplace_back(index[a], index[b]);
    segments.push_back({{"a", index[a]}, {"b", index[b]}, {"kind", kind}});
  };
  for (const auto& s : model.springs) add_declared(s.a, s.b, "spring");
  for (const auto& d : model.dampers) add_declared(d.a, d.b, "damper");
  std::vector<bool> used(np + anchors.size(), false);
  for (const auto& [a, b] : declared) used[a] = used[b] = true;
  std::set<size_t> on_ring;
  for (size_t r : rings) on_ring.insert(guides.point[r]);
  for (const auto& [a, b] : rigid_links(all, extent, declared, 4 * (np + anchors.size()) + 8)) {
    // A point on a drawn hoop is held by the hoop, not by a rod to the hoop's centre.
    if ((on_ring.count(a) && b >= np) || (on_ring.count(b) && a >= np)) continue;
    segments.push_back({{"a", a}, {"b", b}, {"kind", "link"}});
    used[a] = used[b] = true;
  }
  // A moving mass attached to nothing (a spring written as a potential) gets a guide line to
  // where its position expression is anchored. Without particles (energies written by hand) the
  // moving points stand for the masses.
  const bool hand_written = particle_mass.empty() && model.bodies.empty();
  for (size_t i = 0; i < np; ++i)
    if (!used[i] && !on_ring.count(i) && ground_of[i] >= 0 &&
        (hand_written || particle_mass.count(points[i]->name))) {
      segments.push_back({{"a", ground_of[i]}, {"b", i}, {"kind", "guide"}});
      used[i] = used[static_cast<size_t>(ground_of[i])] = true;
    }

  // Points: particles sized by mass (cube root), fixed points, other points, used anchors.
  double heaviest = 0;
  for (size_t j = 0; j < massive.size(); ++j)
    heaviest = std::max(heaviest, statics[3 + 13 * nb + j]);
  const double base = 0.035 * extent;
  // Points are coloured by group: the name up to its first '.', so that an element's points
  // (`cable.n1`, `cable.n2`, …) share a colour; particles of a group of many are beads.
  std::map<std::string, size_t> groups, group_size;
  auto group_of = [](const std::string& name) { return name.substr(0, name.find('.')); };
  for (const Point* p : points) ++group_size[group_of(p->name)];
  nlohmann::json jpoints = nlohmann::json::array();
  std::vector<double> travelled(np, 0.0);
  for (size_t i = 0; i < np; ++i) {
    for (size_t f = 1; f < nf; ++f) travelled[i] += dist(pos[f][i], pos[f - 1][i]);
    const std::string& name = points[i]->name;
    const auto m = std::find(massive.begin(), massive.end(), name);
    nlohmann::json p{{"name", name}};
    double radius = (hand_written ? 0.8 : 0.35) * base;
    if (m != massive.end()) {
      const double mass = statics[3 + 13 * nb + static_cast<size_t>(m - massive.begin())];
      radius = heaviest > 0 && mass > 0 ? base * std::max(0.4, std::cbrt(mass / heaviest)) : base;
      if (group_size[group_of(name)] > 3 || model.find_body(group_of(name))) radius *= 0.4;
      p["kind"] = "particle";
      p["mass"] = mass;
    } else {
      const bool moves = travelled[i] > 1e-6 * extent;
      // Energies written by hand: the moving points are where the masses are.
      p["kind"] = moves ? (hand_written ? "particle" : "point") : "fixed";
    }
    if (const double* s = visual_lookup(visual.size, name)) radius = *s;
    if (const std::string* c = visual_lookup(visual.color, name)) p["color"] = *c;
    p["group"] = groups.emplace(group_of(name), groups.size()).first->second;
    p["radius"] = radius;
    jpoints.push_back(p);
  }
  for (size_t a = 0; a < anchors.size(); ++a)
    jpoints.push_back(
        {{"name", "ground"}, {"kind", used[np + a] ? "anchor" : "unused"}, {"radius", 0.5 * base}});

  // Trails: as the visual section says, or the moving particle (or point) that travels furthest
  // when the moving ones belong to at most four groups.
  nlohmann::json trail = nlohmann::json::array();
  if (visual.trail_given) {
    for (size_t i = 0; i < np; ++i)
      if (visual_listed(visual.trail, points[i]->name)) trail.push_back(i);
  } else {
    long best = -1;
    std::set<std::string> moving_groups;
    // Among the particles, or the moving points when there are none (a robot's tool point).
    bool any_particle = false;
    for (size_t i = 0; i < np; ++i)
      any_particle =
          any_particle || (jpoints[i]["kind"] == "particle" && travelled[i] > 1e-3 * extent);
    const char* candidate = any_particle ? "particle" : "point";
    for (size_t i = 0; i < np; ++i)
      if (jpoints[i]["kind"] == candidate && travelled[i] > 1e-3 * extent) {
        moving_groups.insert(group_of(points[i]->name));
        if (best < 0 || travelled[i] > travelled[static_cast<size_t>(best)])
          best = static_cast<long>(i);
      }
    if (best >= 0 && moving_groups.size() <= 4) trail.push_back(best);
  }

  // The longest bone from each link's joint at the first frame, by link name.
  std::map<std::string, double> link_length;
  if (bones.nodes > 0) {
    const auto& nodes = bones.layout["nodes"];
    for (const auto& t : model.tree)
      if (t.body >= 0) link_length[model.bodies[static_cast<size_t>(t.body)].name] = 0;
    for (const auto& bone : bones.layout["bones"]) {
      const size_t a = bone[0], b = bone[1];
      if (nodes[a]["kind"] != "joint") continue;
      const auto it = link_length.find(nodes[a]["name"].get<std::string>());
      if (it == link_length.end()) continue;
      const double* pa = &joints[0][3 * a];
      const double* pb = &joints[0][3 * b];
      it->second = std::max(it->second, std::hypot(pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]));
    }
  }

  double mean_link = 0;
  size_t measured = 0;
  for (const auto& [name, length] : link_length)
    if (length > 0) mean_link += length, ++measured;
  if (measured > 0) mean_link /= static_cast<double>(measured);

  // Bodies: shape from the declared shape or the inertia, centred on the centre of mass; a URDF
  // link also as its <visual> geometry says, drawn instead when the front end can.
  nlohmann::json jbodies = nlohmann::json::array();
  UrdfVisuals urdf;
  for (size_t j = 0; j < nb; ++j) {
    const double* s = &statics[3 + 13 * j];
    Eigen::Matrix3d I;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) I(r, c) = s[1 + 3 * r + c];
    BodyShape shape = shape_from_inertia(bodies[j]->shape, s[0], I,
                                         Eigen::Vector3d(s[10], s[11], s[12]), 0.08 * extent);
    // A body small against the scene (a kite on a long tether) is enlarged to be seen. A link of
    // a joint tree keeps its size, but is drawn at most 1.2 times as long as the link (its longest
    // bone; a published inertia can be far from the link's solid, the skeleton shows the link).
    const double largest = std::max({shape.size[0], shape.size[1], shape.size[2]});
    const auto bone = link_length.find(bodies[j]->name);
    if (bone != link_length.end()) {
      // A link whose child sits on its joint (a wrist) measures by its centre of mass, or else by
      // the mean link.
      double length = std::max(bone->second, 2 * std::hypot(s[10], s[11], s[12]));
      if (!(length > 0)) length = mean_link;
      if (length > 0 && largest > 1.2 * length)
        for (double& x : shape.size) x *= 1.2 * length / largest;
    } else if (largest < 0.06 * extent) {
      for (double& x : shape.size) x *= 0.06 * extent / largest;
    }
    if (const double* scale = visual_lookup(visual.size, bodies[j]->name))
      for (double& x : shape.size) x *= *scale;
    nlohmann::json b{{"name", bodies[j]->name}, {"shape", shape.kind}};
    b["size"] = {shape.size[0], shape.size[1], shape.size[2]};
    std::vector<double> axes;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) axes.push_back(round_decimals(shape.axes(r, c), 6));
    b["axes"] = axes;
    b["center"] = {s[10], s[11], s[12]};
    if (const std::string* c = visual_lookup(visual.color, bodies[j]->name)) b["color"] = *c;
    if (nlohmann::json v = urdf.of(*bodies[j]); !v.is_null()) b["visuals"] = std::move(v);
    jbodies.push_back(b);
  }

  // The view: up against gravity; a planar model (one axis never changes) is seen face on.
  Eigen::Vector3d g(statics[0], statics[1], statics[2]);
  int flat = -1;
  for (int k = 2; k >= 0 && flat < 0; --k) {
    bool constant = hi[k] - lo[k] <= 1e-9 * extent;
    for (size_t f = 0; f < nf && constant; ++f)
      for (const auto& b : pose[f]) constant = constant && std::abs(b[3 + 4 * k] - 1) < 1e-9;
    if (constant && (np + nb) > 0) flat = k;
  }
  Eigen::Vector3d up(0, 0, 1);
  if (g.norm() > 0 && std::isfinite(g.norm()))
    up = -g.normalized();
  else if (flat == 2)
    up = Eigen::Vector3d(0, 1, 0);

  // extent > 1e-9 but may overflow to inf (points near ±1e308): the cast's range is checked.
  const int decimals =
      4 - static_cast<int>(std::clamp(std::floor(std::log10(extent)), -10.0, 308.0));
  nlohmann::json j;
  j["name"] = model.name;
  j["extent"] = extent;
  j["up"] = {up[0], up[1], up[2]};
  j["normal"] =
      flat >= 0 ? nlohmann::json{int(flat == 0), int(flat == 1), int(flat == 2)} : nlohmann::json();
  j["points"] = jpoints;
  j["bodies"] = jbodies;
  if (!urdf.notes().empty()) j["notes"] = urdf.notes();
  if (urdf.mesh_bytes() > 0) j["mesh_bytes"] = urdf.mesh_bytes();
  j["segments"] = segments;
  j["trail"] = trail;
  std::vector<double> times, flat_pos, flat_pose;
  times.reserve(nf);
  flat_pos.reserve(nf * 3 * all[0].size());
  flat_pose.reserve(nf * 12 * nb);
  const size_t t_col = traj.column_index("t");
  for (size_t f = 0; f < nf; ++f) {
    times.push_back(traj.data[rows[f] * traj.columns.size() + t_col]);
    for (const auto& p : all[f])
      for (double x : p) flat_pos.push_back(round_decimals(x, decimals));
    for (const auto& b : pose[f]) {
      for (size_t k = 0; k < 3; ++k) flat_pose.push_back(round_decimals(b[k], decimals));
      for (size_t k = 3; k < 12; ++k) flat_pose.push_back(round_decimals(b[k], 5));
    }
  }
  j["t"] = times;
  j["positions"] = flat_pos;
  j["poses"] = flat_pose;
  if (!rings.empty()) {
    nlohmann::json jr{{"points", nlohmann::json::array()}, {"samples", kRing}};
    for (size_t r : rings) jr["points"].push_back(guides.point[r]);
    std::vector<double> at;
    for (size_t f = 0; f < nf; ++f)
      for (size_t r : rings)
        for (size_t k = 0; k < 3 * kRing; ++k)
          at.push_back(round_decimals(curves[f][3 * (kRing + 1) * r + k], decimals));
    jr["positions"] = at;
    j["rings"] = jr;
  }
  if (bones.nodes > 0) {
    nlohmann::json sk = bones.layout;
    std::vector<double> at, axes;
    for (size_t f = 0; f < nf; ++f) {
      for (size_t k = 0; k < 3 * bones.nodes; ++k)
        at.push_back(round_decimals(joints[f][k], decimals));
      for (size_t k = 3 * bones.nodes; k < joints[f].size(); ++k)
        axes.push_back(round_decimals(joints[f][k], 5));
    }
    sk["positions"] = at;
    sk["directions"] = axes;
    j["skeleton"] = sk;
  }
  return j;
}

}  // namespace lagrange::io
