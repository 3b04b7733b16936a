#include "io/report_urdf.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lagrange/rigid_body.hpp"

namespace lagrange::io {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

struct UrdfVisuals::File {
  tinyxml2::XMLDocument doc;
  bool ok = false;
  std::map<std::string, const XMLElement*> links;
  std::map<std::string, std::string> material_rgba;  // robot-level <material name> colours
};

namespace {

// Numbers of an attribute ("0.1 0 0.3"), `fallback` when absent or malformed.
std::vector<double> numbers(const XMLElement* e, const char* name, std::vector<double> fallback) {
  const char* text = e ? e->Attribute(name) : nullptr;
  if (!text) return fallback;
  std::istringstream in(text);
  std::vector<double> out;
  double x = 0;
  while (in >> x) out.push_back(x);
  if (!in.eof() || out.size() != fallback.size()) return fallback;
  for (double v : out)
    if (!std::isfinite(v)) return fallback;
  return out;
}

// "#rrggbb" and the opacity of an rgba attribute's "r g b a" in [0, 1].
bool rgba_color(const std::string& rgba, nlohmann::json& v) {
  std::istringstream in(rgba);
  double c[4];
  for (double& x : c)
    if (!(in >> x) || !std::isfinite(x)) return false;
  const auto byte = [](double x) {
    return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255));
  };
  v["color"] = fmt::format("#{:02x}{:02x}{:02x}", byte(c[0]), byte(c[1]), byte(c[2]));
  v["opacity"] = std::clamp(c[3], 0.0, 1.0);
  return true;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

}  // namespace

std::string base64(const std::string& bytes) {
  static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned n = static_cast<unsigned char>(bytes[i]) << 16 |
                       static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[n >> 18], table[(n >> 12) & 63], table[(n >> 6) & 63], table[n & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned n = static_cast<unsigned char>(bytes[i]) << 16;
    out += {table[n >> 18], table[(n >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned n =
        static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += {table[n >> 18], table[(n >> 12) & 63], table[(n >> 6) & 63], '='};
  }
  return out;
}

std::string resolve_mesh(const std::string& filename, const std::string& urdf_path) {
  std::error_code ec;
  const fs::path folder = fs::absolute(fs::path(urdf_path), ec).parent_path();
  std::vector<fs::path> candidates;
  const std::string package = "package://", file = "file://";
  if (filename.rfind(package, 0) == 0) {
    const std::string rest = filename.substr(package.size());
    const size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (const char* paths = std::getenv("ROS_PACKAGE_PATH")) {
      std::istringstream in(paths);
      std::string dir;
      while (std::getline(in, dir, ':'))
        if (!dir.empty()) candidates.push_back(fs::path(dir) / name / inside);
    }
    for (fs::path at = folder; !at.empty(); at = at.parent_path()) {
      if (at.filename() == name) candidates.push_back(at / inside);
      candidates.push_back(at / name / inside);
      if (at == at.parent_path()) break;
    }
  } else if (filename.rfind(file, 0) == 0) {
    candidates.push_back(filename.substr(file.size()));
  } else {
    const fs::path p = filename;
    candidates.push_back(p.is_absolute() ? p : folder / p);
  }
  for (const fs::path& c : candidates)
    if (is_file(c)) return c.lexically_normal().string();
  return "";
}

UrdfVisuals::UrdfVisuals() = default;
UrdfVisuals::~UrdfVisuals() = default;

UrdfVisuals::File* UrdfVisuals::file(const std::string& path) {
  auto& slot = files_[path];
  if (slot) return slot->ok ? slot.get() : nullptr;
  slot = std::make_unique<File>();
  if (slot->doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) return nullptr;
  const XMLElement* robot = slot->doc.FirstChildElement("robot");
  if (!robot) return nullptr;
  for (const XMLElement* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link"))
    if (e->Attribute("name")) slot->links[e->Attribute("name")] = e;
  for (const XMLElement* e = robot->FirstChildElement("material"); e;
       e = e->NextSiblingElement("material")) {
    const XMLElement* color = e->FirstChildElement("color");
    if (e->Attribute("name") && color && color->Attribute("rgba"))
      slot->material_rgba[e->Attribute("name")] = color->Attribute("rgba");
  }
  slot->ok = true;
  return slot.get();
}

nlohmann::json UrdfVisuals::of(const Body& body) {
  const std::string& path = body.loc.file;
  if (lower(fs::path(path).extension().string()) != ".urdf") return nullptr;
  File* f = file(path);
  if (!f) return nullptr;
  const auto link = f->links.find(body.name);
  if (link == f->links.end()) return nullptr;
  nlohmann::json out = nlohmann::json::array();
  size_t bytes = 0;
  for (const XMLElement* visual = link->second->FirstChildElement("visual"); visual;
       visual = visual->NextSiblingElement("visual")) {
    const XMLElement* geometry = visual->FirstChildElement("geometry");
    if (!geometry) continue;
    nlohmann::json v;
    if (const XMLElement* box = geometry->FirstChildElement("box")) {
      v = {{"type", "box"}, {"size", numbers(box, "size", {0, 0, 0})}};
    } else if (const XMLElement* cyl = geometry->FirstChildElement("cylinder")) {
      v = {{"type", "cylinder"},
           {"radius", numbers(cyl, "radius", {0})[0]},
           {"length", numbers(cyl, "length", {0})[0]}};
    } else if (const XMLElement* sphere = geometry->FirstChildElement("sphere")) {
      v = {{"type", "sphere"}, {"radius", numbers(sphere, "radius", {0})[0]}};
    } else if (const XMLElement* mesh = geometry->FirstChildElement("mesh")) {
      const std::string name = mesh->Attribute("filename") ? mesh->Attribute("filename") : "";
      const std::string format = lower(fs::path(name).extension().string());
      if (format != ".stl" && format != ".obj" && format != ".dae") {
        notes_.push_back(
            fmt::format("link '{}': mesh '{}' is not STL, OBJ or COLLADA; the link "
                        "is drawn from its inertia",
                        body.name, name));
        return nullptr;
      }
      const std::string found = resolve_mesh(name, path);
      if (found.empty()) {
        notes_.push_back(fmt::format(
            "link '{}': mesh '{}' not found (package:// is looked up in --package-path, "
            "$ROS_PACKAGE_PATH and beside the URDF); the link is drawn "
            "from its inertia",
            body.name, name));
        return nullptr;
      }
      std::ifstream in(found, std::ios::binary);
      std::ostringstream data;
      data << in.rdbuf();
      if (!in) {
        notes_.push_back(
            fmt::format("link '{}': cannot read mesh '{}'; the link is drawn from its "
                        "inertia",
                        body.name, found));
        return nullptr;
      }
      const std::string text = data.str();
      bytes += text.size();
      if (mesh_bytes_ + bytes > kMaxMeshBytes) {
        notes_.push_back(
            fmt::format("link '{}': meshes beyond the report's {} MiB; the link is "
                        "drawn from its inertia",
                        body.name, kMaxMeshBytes >> 20));
        return nullptr;
      }
      v = {{"type", "mesh"},
           {"format", format.substr(1)},
           {"data", base64(text)},
           {"scale", numbers(mesh, "scale", {1, 1, 1})}};
    } else {
      continue;
    }
    const XMLElement* origin = visual->FirstChildElement("origin");
    v["origin"] = numbers(origin, "xyz", {0, 0, 0});
    const std::vector<double> rpy = numbers(origin, "rpy", {0, 0, 0});
    v["rotation"] = rotation_from_euler(rpy[0], rpy[1], rpy[2]);  // URDF's Rz(y) Ry(p) Rx(r)
    if (const XMLElement* material = visual->FirstChildElement("material")) {
      const XMLElement* color = material->FirstChildElement("color");
      if (color && color->Attribute("rgba")) {
        rgba_color(color->Attribute("rgba"), v);
      } else if (material->Attribute("name")) {
        const auto named = f->material_rgba.find(material->Attribute("name"));
        if (named != f->material_rgba.end()) rgba_color(named->second, v);
      }
    }
    out.push_back(std::move(v));
  }
  if (out.empty()) return nullptr;
  mesh_bytes_ += bytes;
  return out;
}

}  // namespace lagrange::io
