#include <fmt/format.h>

#include "model/model_reader.hpp"

namespace lagrange::model {

void ModelReader::read_particles(const YAML::Node& node) {
  auto add = [&](const YAML::Node& point, const YAML::Node& mass, const YAML::Node& at) {
    std::string name = point_name(point, "a particle");
    GiNaC::ex m = scalar_expr(mass, kAll, fmt::format("mass of the particle at '{}'", name));
    check_sign(m, mass, true, fmt::format("mass for the particle at '{}'", name));
    m_.particles.push_back(Particle{name, m, src_.at(at)});
  };
  if (node.IsMap()) {
    check_keys(node, {}, "particles");
    for (const auto& kv : node) add(kv.first, kv.second, kv.first);
    return;
  }
  expect_seq(node, "particles (a list of {point, mass} or a map point: mass)");
  for (const auto& item : node) {
    check_keys(item, {"point", "mass"}, "a particle");
    if (!item["point"] || !item["mass"])
      fail(item, "expected 'point' and 'mass' in a particle, got only one");
    add(item["point"], item["mass"], item);
  }
}

// A body-frame force at a body point is turned to the world frame here: F = R F_b.
void ModelReader::read_forces(const YAML::Node& node) {
  expect_seq(node, "forces (a list of {point, force, frame})");
  for (const auto& item : node) {
    check_keys(item, {"point", "force", "frame"}, "a force");
    if (!item["point"] || !item["force"])
      fail(item, "expected 'point' and 'force' in a force, got only one");
    std::string name = point_name(item["point"], "a force");
    Vec3 f = vector_expr(item["force"], kAll, fmt::format("force at '{}'", name));
    if (item["frame"]) {
      const std::string frame = scalar(item["frame"], "frame of a force");
      const NameEntry& e = names_.at(name);
      if (frame != "world" && frame != "body")
        fail(item["frame"], fmt::format("expected 'world' or 'body' for the frame of the force at "
                                        "'{}', got '{}'",
                                        name, clip(frame)));
      if (frame == "body" && e.kind != NameKind::BodyPoint)
        fail(item["frame"], fmt::format("expected a body point (body.point) for a body-frame "
                                        "force, got point '{}'",
                                        name));
      if (frame == "body") {
        const Mat3 R = m_.find_body(e.owner)->rot();
        const Vec3 fb = f;
        for (size_t i = 0; i < 3; ++i) f[i] = R[i][0] * fb[0] + R[i][1] * fb[1] + R[i][2] * fb[2];
      }
    }
    m_.forces.push_back(PointForce{name, f, src_.at(item)});
  }
}

std::pair<std::string, std::string> ModelReader::read_between(const YAML::Node& item,
                                                              const std::string& what) {
  const YAML::Node between = item["between"];
  if (!between) fail(item, fmt::format("expected 'between: [point, point]' in {}, got none", what));
  if (!between.IsSequence() || between.size() != 2)
    fail(between, fmt::format("expected two point names [a, b] for 'between' of {}, got {}", what,
                              describe(between)));
  return {point_name(between[0], what), point_name(between[1], what)};
}

void ModelReader::read_springs(const YAML::Node& node) {
  expect_seq(node, "springs (a list of {between, k, l0})");
  for (const auto& item : node) {
    check_keys(item, {"between", "k", "l0"}, "a spring");
    auto [a, b] = read_between(item, "a spring");
    std::string what = fmt::format("spring between '{}' and '{}'", a, b);
    if (!item["k"]) fail(item, fmt::format("expected 'k' in the {}, got none", what));
    GiNaC::ex k = scalar_expr(item["k"], kAll, "k of the " + what);
    check_sign(k, item["k"], false, "spring constant k");
    GiNaC::ex l0 = 0;
    if (item["l0"]) {
      l0 = scalar_expr(item["l0"], kAll, "l0 of the " + what);
      check_sign(l0, item["l0"], false, "rest length l0");
    }
    m_.springs.push_back(Spring{a, b, k, l0, src_.at(item)});
  }
}

void ModelReader::read_dampers(const YAML::Node& node) {
  expect_seq(node, "dampers (a list of {between, c})");
  for (const auto& item : node) {
    check_keys(item, {"between", "c"}, "a damper");
    auto [a, b] = read_between(item, "a damper");
    std::string what = fmt::format("damper between '{}' and '{}'", a, b);
    if (!item["c"]) fail(item, fmt::format("expected 'c' in the {}, got none", what));
    GiNaC::ex c = scalar_expr(item["c"], kAll, "c of the " + what);
    check_sign(c, item["c"], false, "damping coefficient c");
    m_.dampers.push_back(Damper{a, b, c, src_.at(item)});
  }
}

}  // namespace lagrange::model
