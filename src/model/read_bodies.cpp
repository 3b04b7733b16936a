#include <fmt/format.h>

#include "lagrange/rigid_body.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

// Bodies are read in the order written, so that a posed body may use earlier bodies
// (`rotation: link1.R * rot_z(q2)`); their points then join the model's points.
void ModelReader::read_bodies(const YAML::Node& node) {
  body_ready_.assign(node.size(), false);
  size_t i = 0;
  for (const auto& kv : node) {
    m_.bodies.push_back(read_body(kv.first.Scalar(), kv.first, kv.second));
    body_ready_[i++] = true;
  }
}

// docs/theory.md §4.4: a free body owns r ∈ R³, R ∈ SO(3) and ṙ, ω; a posed body follows
// position and rotation, expressions of the other coordinates.
Body ModelReader::read_body(const std::string& name, const YAML::Node& key,
                            const YAML::Node& spec) {
  const std::string what = fmt::format("body '{}'", name);
  if (!spec.IsMap())
    fail(spec.IsNull() ? key : spec,
         fmt::format("expected a map {{mass, inertia or shape, frame or position/rotation}} for "
                     "{}, got {}",
                     what, describe(spec)));
  check_keys(
      spec,
      {"mass", "inertia", "shape", "com", "frame", "initial", "position", "rotation", "points"},
      what);
  Body body;
  body.name = name;
  body.loc = src_.at(key);
  if (!spec["mass"]) fail(key, fmt::format("expected 'mass' in {}, got none", what));
  body.mass = scalar_expr(spec["mass"], kParams, "mass of " + what);
  check_sign(body.mass, spec["mass"], true, "mass for " + what);
  if (spec["com"]) body.com = vector_expr(spec["com"], kParams, "centre of mass of " + what);
  body.inertia = read_inertia(body, spec);
  if (spec["shape"]) body.shape = spec["shape"].begin()->first.Scalar();  // one, read_shape checked

  const bool posed = spec["position"] || spec["rotation"];
  if (spec["frame"]) {
    const std::string frame = scalar(spec["frame"], "frame of " + what);
    if (frame != "free")
      fail(spec["frame"], fmt::format("expected 'free' for the frame of {} (or position and "
                                      "rotation instead of a frame), got '{}'",
                                      what, clip(frame)));
    if (posed)
      fail(spec[spec["position"] ? "position" : "rotation"],
           fmt::format("expected either 'frame: free' or a pose (position, rotation) in {}, got "
                       "both",
                       what));
    if (!spec["initial"])
      fail(key, fmt::format("expected 'initial: {{position, orientation, velocity, omega}}' in "
                            "the free {}, got none",
                            what));
    body.make_free();
    read_free_initial(body, spec["initial"]);
  } else {
    if (!posed)
      fail(key, fmt::format("expected 'frame: free' or a pose (position, rotation) in {}, got "
                            "neither",
                            what));
    if (spec["initial"])
      fail(spec["initial"], fmt::format("expected 'initial' only in a free body, got it in the "
                                        "posed {} (its state follows the coordinates)",
                                        what));
    if (spec["position"])
      body.position = vector_expr(spec["position"], kAll, "position of " + what);
    if (spec["rotation"]) {
      body.rotation = matrix_expr(spec["rotation"], kAll, "rotation of " + what);
      check_posed_rotation(body, spec["rotation"]);
    }
  }
  check_inertia(body, body.free ? std::nullopt : single_spin_axis(body));
  if (spec["points"]) read_body_points(body, spec["points"]);
  return body;
}

Mat3 ModelReader::read_inertia(const Body& body, const YAML::Node& spec) {
  const std::string what = fmt::format("inertia of body '{}'", body.name);
  if (spec["inertia"] && spec["shape"])
    fail(spec["shape"],
         fmt::format("expected either 'inertia' or 'shape' in body '{}', got both", body.name));
  if (spec["shape"]) return read_shape(body, spec["shape"]);
  if (!spec["inertia"])
    fail(spec, fmt::format("expected 'inertia: [Ixx, Iyy, Izz]', a 3×3 'inertia' or a 'shape' in "
                           "body '{}', got none",
                           body.name));
  const YAML::Node& node = spec["inertia"];
  if (node.IsSequence() && node.size() == 3 && node[0].IsScalar()) {
    const Vec3 p = vector_expr(node, kParams, "principal " + what);
    return principal_inertia(p[0], p[1], p[2]);
  }
  if (!node.IsSequence())
    fail(node, fmt::format("expected principal moments [Ixx, Iyy, Izz] or a 3×3 tensor for the "
                           "{}, got {}",
                           what, describe(node)));
  return matrix_expr(node, kParams, what);
}

// docs/theory.md §4.8: box I_xx = m(b² + c²)/12 (cyclic), cylinder along z, solid sphere.
Mat3 ModelReader::read_shape(const Body& body, const YAML::Node& shape) {
  const std::string what = fmt::format("shape of body '{}'", body.name);
  check_keys(shape, {"box", "cylinder", "sphere"}, what);
  if (shape.size() != 1)
    fail(shape, fmt::format("expected one of box, cylinder, sphere in the {}, got {}", what,
                            shape.size()));
  auto length = [&](const YAML::Node& n, const std::string& which) {
    GiNaC::ex e = scalar_expr(n, kParams, which + " of body '" + body.name + "'");
    check_sign(e, n, true, which);
    return e;
  };
  auto required = [&](const YAML::Node& map, const char* key, const std::string& kind) {
    if (!map[key])
      fail(map,
           fmt::format("expected '{}' in the {} of body '{}', got none", key, kind, body.name));
    return map[key];
  };
  if (const YAML::Node box = shape["box"]) {
    if (!box.IsSequence() || box.size() != 3)
      fail(box, fmt::format("expected edge lengths [a, b, c] for the box of body '{}', got {}",
                            body.name, describe(box)));
    return box_inertia(body.mass, length(box[0], "box edge a"), length(box[1], "box edge b"),
                       length(box[2], "box edge c"));
  }
  if (const YAML::Node cyl = shape["cylinder"]) {
    check_keys(cyl, {"radius", "length"}, "the cylinder of body '" + body.name + "'");
    return cylinder_inertia(body.mass,
                            length(required(cyl, "radius", "cylinder"), "cylinder radius"),
                            length(required(cyl, "length", "cylinder"), "cylinder length"));
  }
  const YAML::Node sphere = shape["sphere"];
  check_keys(sphere, {"radius"}, "the sphere of body '" + body.name + "'");
  return sphere_inertia(body.mass, length(required(sphere, "radius", "sphere"), "sphere radius"));
}

// Points fixed in the body: `body.p` is r + R p_b in the world frame (Body::world_point).
void ModelReader::read_body_points(Body& body, const YAML::Node& node) {
  check_keys(node, {}, fmt::format("points of body '{}'", body.name));
  for (const auto& kv : node) {
    declare_body_point(body.name, kv.first, body_points_.size());
    const std::string name = body.name + "." + kv.first.Scalar();
    const Vec3 p = vector_expr(kv.second, kParams, fmt::format("body point '{}'", name));
    body_points_.push_back(Point{name, body.world_point(p), src_.at(kv.first)});
  }
}

// Torques by virtual power τ·ω (docs/theory.md §4.4: F_rot = 2P(F_R)).
void ModelReader::read_torques(const YAML::Node& node) {
  expect_seq(node, "torques (a list of {body, torque, frame})");
  for (const auto& item : node) {
    check_keys(item, {"body", "torque", "frame"}, "a torque");
    if (!item["body"] || !item["torque"])
      fail(item, "expected 'body' and 'torque' in a torque, got only one");
    const std::string name = scalar(item["body"], "the body of a torque");
    if (m_.find_body(name) == nullptr)
      fail(item["body"], fmt::format("expected a body name for a torque, got '{}' (bodies: {})",
                                     clip(name), names_of(NameKind::Body)));
    BodyTorque tq{name, vector_expr(item["torque"], kAll, fmt::format("torque on '{}'", name)),
                  false, src_.at(item)};
    if (item["frame"]) {
      const std::string frame = scalar(item["frame"], "frame of a torque");
      if (frame != "world" && frame != "body")
        fail(item["frame"],
             fmt::format("expected 'world' or 'body' for the frame of the torque on '{}', got "
                         "'{}'",
                         name, clip(frame)));
      tq.body_frame = frame == "body";
    }
    m_.torques.push_back(tq);
  }
}

}  // namespace lagrange::model
