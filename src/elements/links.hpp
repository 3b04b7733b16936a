#pragma once
// Joint chains (docs/model-language.md, "Links and joints"; docs/theory.md §4.8): a tree of links
// joined by revolute, prismatic or fixed joints, read from `links:` or a URDF file, lowered into
// posed bodies, one coordinate per movable joint and the joint torques as generalised forces.

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

#include "lagrange/model.hpp"
#include "model/vec3_algebra.hpp"

namespace lagrange::model {
class ModelReader;
}

namespace lagrange::elements {

/// The joint that attaches a link to its parent, in the parent's frame (URDF conventions).
struct JointSpec {
  enum class Type { Revolute, Prismatic, Fixed } type = Type::Fixed;
  std::string name;              ///< the coordinate's name (movable joints)
  Vec3 axis{0, 0, 1};            ///< joint axis in the joint frame (normalised when lowered)
  Vec3 xyz{0, 0, 0};             ///< origin of the joint frame in the parent frame
  Vec3 rpy{0, 0, 0};             ///< its orientation: R = R_z(yaw) R_y(pitch) R_x(roll)
  std::optional<Mat3> rotation;  ///< the orientation as a matrix, replacing rpy (from `dh:`)
  double initial = 0, rate = 0;
  std::optional<GiNaC::ex> torque;  ///< joint torque (force for prismatic), read when lowered
  GiNaC::ex damping = 0;            ///< viscous joint damping: adds −b q̇
  SourceLoc loc;
  SourceLoc axis_loc;  ///< where the axis is written (loc when it is not)
};

/// Denavit–Hartenberg parameters of a link (`dh:`), θ and d the constant parts (the joint adds q
/// to θ, or to d for a prismatic joint). Standard (Spong): A = R_z(θ) T_z(d) T_x(a) R_x(α), the
/// joint about the parent's z and the link frame at the far end; modified (Craig): A = R_x(α)
/// T_x(a) R_z(θ) T_z(d) with α, a of the parent's row, the link frame on the joint axis.
struct DhSpec {
  bool modified = false;
  GiNaC::ex a = 0, alpha = 0, d = 0, theta = 0;
};

/// A link: its joint, mass properties (inertia about the centre of mass, link axes) and points.
struct LinkSpec {
  std::string name;
  int parent = -1;  ///< index of the parent link, −1 for the fixed world frame
  JointSpec joint;
  GiNaC::ex mass = 0;  ///< 0: a massless frame (no body)
  Vec3 com{0, 0, 0};
  Mat3 inertia{Vec3{0, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 0}};
  std::vector<std::pair<std::string, Vec3>> points;  ///< link-frame points `<link>.<name>`
  std::optional<DhSpec> dh;                          ///< joint placed by DH parameters
  YAML::Node key, spec;                              ///< YAML source (null for URDF links)
  SourceLoc loc;
  SourceLoc inertia_loc;  ///< where the mass properties are written (loc when they are not)
};

/// A chain after lowering: the coordinate of each link's joint (or −1) and where torques go.
struct LinkChain {
  std::string title;
  std::string robot;  ///< a URDF's <robot name> (empty for `links:`)
  std::vector<LinkSpec> links;
  std::vector<int> coordinate;  ///< per link: index in Model::coordinates, −1 for fixed joints
};

/// Rotation R_z(yaw) R_y(pitch) R_x(roll) (URDF's rpy), exact.
Mat3 rpy_rotation(const Vec3& rpy);
/// Rotation by `angle` about the unit axis `k` (Rodrigues; rot_x/y/z for ±e_x, ±e_y, ±e_z).
Mat3 axis_angle_rotation(const Vec3& k, const GiNaC::ex& angle);
using model::mat_mul;  // a·b for 3×3 matrices (model/vec3_algebra.hpp)
using model::mat_vec;  // A v

/// Phase 1: a coordinate per movable joint (declared under the joint's name), a posed body per
/// link with mass (pose = product of the joint transforms), link points. Links come parents
/// first.
void declare_chain(model::ModelReader& reader, LinkChain& chain);
/// Phase 2: joint torques and damping as generalised forces, the summary `derive` prints.
void lower_chain(model::ModelReader& reader, const LinkChain& chain);

/// Places the joints of links with `dh:` (axis z, origin from the parameters and the parent's DH
/// frame) and moves standard-DH links' centre of mass, inertia and points from the DH frame into
/// the joint frame. Links parents first.
void apply_dh(LinkChain& chain);

/// `links:` in a model file.
void declare_links(model::ModelReader& reader, const YAML::Node& node, LinkChain& chain);
void lower_links(model::ModelReader& reader, LinkChain& chain);

/// A URDF file as a chain, links parents first (ModelError at the file's line for a missing
/// link, a cycle, an unsupported or mimic joint, a negative mass, malformed numbers).
LinkChain read_urdf(const std::string& path);
/// `urdf:` in a model file: the file (relative to the model file) and initial joint values.
void declare_urdf(model::ModelReader& reader, const YAML::Node& node, LinkChain& chain);

}  // namespace lagrange::elements
