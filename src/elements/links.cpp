// `links:` (docs/model-language.md, "Links and joints"): a tree of links written parents first,
// each with the joint that attaches it to its parent.

#include "elements/links.hpp"

#include <fmt/format.h>

#include "model/model_reader.hpp"

namespace lagrange::elements {

namespace {

using model::ModelReader;

JointSpec::Type joint_type(const ModelReader& r, const YAML::Node& node, const std::string& what) {
  const std::string type = r.scalar(node, "type of " + what);
  if (type == "revolute" || type == "continuous") return JointSpec::Type::Revolute;
  if (type == "prismatic") return JointSpec::Type::Prismatic;
  if (type == "fixed") return JointSpec::Type::Fixed;
  r.fail(node, fmt::format("expected revolute, continuous, prismatic or fixed for the type of {}, "
                           "got '{}'",
                           what, model::clip(type)));
}

JointSpec read_joint(const ModelReader& r, const std::string& link, const YAML::Node& key,
                     const YAML::Node& node) {
  JointSpec j;
  const std::string what = fmt::format("the joint of link '{}'", link);
  if (!node)
    r.fail(key, fmt::format("expected 'joint: {{name, type, axis, origin, …}}' in link '{}', got "
                            "none",
                            link));
  r.expect_map(node, what + " ({name, type, axis, origin, initial, rate, torque, damping})");
  r.check_keys(node, {"name", "type", "axis", "origin", "initial", "rate", "torque", "damping"},
               what);
  if (!node["type"]) r.fail(node, fmt::format("expected 'type' in {}, got none", what));
  j.type = joint_type(r, node["type"], what);
  j.loc = r.source().at(node);
  const bool fixed = j.type == JointSpec::Type::Fixed;
  if (fixed) {
    for (const char* k : {"name", "axis", "initial", "rate", "torque", "damping"})
      if (node[k])
        r.fail(node[k],
               fmt::format("expected no '{}' in {}: a fixed joint has no coordinate", k, what));
  } else {
    if (!node["name"])
      r.fail(node, fmt::format("expected 'name' (its coordinate's name) in {}, got none", what));
    j.name = r.scalar(node["name"], "name of " + what);
    j.loc = r.source().at(node["name"]);
    j.axis_loc = j.loc;
    if (node["axis"]) {
      j.axis = r.vector_expr(node["axis"], model::kParams, "axis of " + what);
      j.axis_loc = r.source().at(node["axis"]);
    }
    if (node["initial"]) {
      j.initial = r.number(node["initial"], model::kParams, "initial value of joint " + j.name);
      if (j.type == JointSpec::Type::Revolute)
        r.warn_implausible(j.initial, node["initial"], ModelReader::Quantity::Angle,
                           "the initial angle of revolute joint '" + j.name + "'");
    }
    if (node["rate"]) j.rate = r.number(node["rate"], model::kParams, "rate of joint " + j.name);
    if (node["damping"]) {
      j.damping = r.scalar_expr(node["damping"], model::kParams, "damping of joint " + j.name);
      r.check_sign(j.damping, node["damping"], false, "damping of joint " + j.name);
    }
  }
  if (const YAML::Node origin = node["origin"]) {
    r.expect_map(origin, "origin of " + what + " ({xyz, rpy})");
    r.check_keys(origin, {"xyz", "rpy"}, "origin of " + what);
    if (origin["xyz"])
      j.xyz = r.vector_expr(origin["xyz"], model::kParams, "origin xyz of " + what);
    if (origin["rpy"])
      j.rpy = r.vector_expr(origin["rpy"], model::kParams, "origin rpy of " + what);
  }
  return j;
}

// `dh: {convention: standard | modified, a, alpha, d, theta}`: the joint's place instead of its
// `origin` and `axis`.
DhSpec read_dh(const ModelReader& r, const std::string& link, const YAML::Node& node,
               const YAML::Node& joint) {
  const std::string what = fmt::format("dh of link '{}'", link);
  r.expect_map(node, what + " ({convention, a, alpha, d, theta})");
  r.check_keys(node, {"convention", "a", "alpha", "d", "theta"}, what);
  if (!node["convention"])
    r.fail(node, fmt::format("expected 'convention: standard' or 'convention: modified' in {}, "
                             "got none",
                             what));
  const std::string convention = r.scalar(node["convention"], "convention of " + what);
  if (convention != "standard" && convention != "modified")
    r.fail(node["convention"], fmt::format("expected standard or modified for the convention of "
                                           "{}, got '{}'",
                                           what, model::clip(convention)));
  for (const char* k : {"origin", "axis"})
    if (joint && joint[k])
      r.fail(joint[k], fmt::format("expected no '{}' in the joint of link '{}': its 'dh' places "
                                   "the joint (axis z)",
                                   k, link));
  DhSpec dh;
  dh.modified = convention == "modified";
  for (auto [key, value] : {std::pair{"a", &dh.a}, std::pair{"alpha", &dh.alpha},
                            std::pair{"d", &dh.d}, std::pair{"theta", &dh.theta}})
    if (node[key])
      *value = r.scalar_expr(node[key], model::kParams, fmt::format("{} in {}", key, what));
  return dh;
}

}  // namespace

void declare_links(ModelReader& r, const YAML::Node& node, LinkChain& chain) {
  r.expect_map(node,
               "links (a map name: {parent, joint, dh, mass, com, inertia or shape, points})");
  r.check_keys(node, {}, "links");
  chain.title = "Links (joint chain)";
  for (const auto& kv : node) {
    LinkSpec link;
    link.name = kv.first.Scalar();
    link.key = kv.first;
    link.spec = kv.second;
    link.loc = r.source().at(kv.first);
    const std::string what = fmt::format("link '{}'", link.name);
    const YAML::Node& spec = kv.second;
    r.expect_map(spec, what + " (a map {parent, joint, mass, com, inertia or shape, points})");
    r.check_keys(spec, {"parent", "joint", "dh", "mass", "com", "inertia", "shape", "points"},
                 what);
    if (spec["parent"]) {
      const std::string parent = r.scalar(spec["parent"], "parent of " + what);
      if (parent != "world") {
        std::string names;
        for (size_t i = 0; i < chain.links.size(); ++i) {
          if (chain.links[i].name == parent) link.parent = static_cast<int>(i);
          names += ", " + chain.links[i].name;
        }
        if (link.parent < 0)
          r.fail(spec["parent"],
                 fmt::format("expected 'world' or a link written before {} as its "
                             "parent, got '{}' (links before it: {})",
                             what, model::clip(parent), names.empty() ? "none" : names.substr(2)));
      }
    }
    link.joint = read_joint(r, link.name, kv.first, spec["joint"]);
    if (spec["dh"]) link.dh = read_dh(r, link.name, spec["dh"], spec["joint"]);
    if (!spec["mass"]) r.fail(kv.first, fmt::format("expected 'mass' in {}, got none", what));
    link.mass = r.scalar_expr(spec["mass"], model::kParams, "mass of " + what);
    r.check_sign(link.mass, spec["mass"], true, "mass for " + what);
    if (spec["com"])
      link.com = r.vector_expr(spec["com"], model::kParams, "centre of mass of " + what);
    Body shape_of;
    shape_of.name = link.name;
    shape_of.mass = link.mass;
    link.inertia = r.read_inertia(shape_of, spec);
    link.inertia_loc = r.source().at(spec["inertia"] ? spec["inertia"]
                                     : spec["shape"] ? spec["shape"]
                                                     : spec["mass"]);
    if (const YAML::Node points = spec["points"]) {
      r.expect_map(points, "points of " + what + " (a map name: [x, y, z])");
      r.check_keys(points, {}, "points of " + what);
      for (const auto& p : points)
        link.points.emplace_back(
            r.scalar(p.first, "point name"),
            r.vector_expr(p.second, model::kParams,
                          fmt::format("point '{}.{}'", link.name, p.first.Scalar())));
    }
    chain.links.push_back(std::move(link));
  }
  apply_dh(chain);
  declare_chain(r, chain);
}

void lower_links(ModelReader& r, LinkChain& chain) {
  for (LinkSpec& link : chain.links) {
    const YAML::Node torque = link.spec["joint"]["torque"];
    if (torque)
      link.joint.torque =
          r.scalar_expr(torque, model::kAll, fmt::format("torque of joint '{}'", link.joint.name));
  }
  lower_chain(r, chain);
}

}  // namespace lagrange::elements
