#pragma once
// The report's drawing of URDF links (issue 36 item 13): each link's <visual> geometry (boxes,
// cylinders, spheres, STL/OBJ/COLLADA meshes embedded in the page), read again from the URDF
// file the link's body came from, in the body's own (link) frame.

#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lagrange/model.hpp"

namespace lagrange::io {

/// Reads the URDF files of a model's bodies once each and gives each link's visuals.
class UrdfVisuals {
 public:
  /// At most this many bytes of meshes are embedded in one report; a body whose meshes would
  /// exceed it keeps the inertia drawing.
  static constexpr size_t kMaxMeshBytes = 32u << 20;

  UrdfVisuals();
  ~UrdfVisuals();

  /// The visuals of the URDF link `body` was read from (its loc.file ends in .urdf), as JSON:
  /// [{"type": "box", "size": [x, y, z]} | {"type": "cylinder", "radius", "length"} (along z) |
  /// {"type": "sphere", "radius"} | {"type": "mesh", "format": "stl"|"obj"|"dae", "data": base64,
  /// "scale": [x, y, z]}, each with "origin" [x, y, z], "rotation" (9, row-major, link frame)
  /// and "color" ("#rrggbb") and "opacity" when the URDF gives a colour]. Null when the body is
  /// no URDF link, the link has no <visual>, or a mesh of it cannot be had (then a note says so).
  nlohmann::json of(const Body& body);

  /// What could not be drawn as the URDF says (missing or unreadable meshes), one line each.
  const std::vector<std::string>& notes() const { return notes_; }
  /// Bytes of mesh files embedded so far.
  size_t mesh_bytes() const { return mesh_bytes_; }

 private:
  struct File;
  File* file(const std::string& path);
  std::map<std::string, std::unique_ptr<File>> files_;
  std::vector<std::string> notes_;
  size_t mesh_bytes_ = 0;
};

/// Where a URDF mesh filename points: `package://NAME/rest` in each folder of $ROS_PACKAGE_PATH
/// (NAME/rest) and in the URDF's folder and its ancestors (a folder named NAME, or holding
/// NAME/); `file://path`; a relative path against the URDF's folder. The first existing file, or
/// "" when none exists.
std::string resolve_mesh(const std::string& filename, const std::string& urdf_path);

/// Standard base64 of `bytes`.
std::string base64(const std::string& bytes);

}  // namespace lagrange::io
