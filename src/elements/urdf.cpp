// URDF robots (docs/model-language.md, "URDF robots"): a URDF file read with tinyxml2 into a
// joint chain. Joint origins (xyz, rpy), axes, inertial origins (xyz and rpy), full inertia
// tensors, fixed and continuous joints and joint damping are honoured; geometry (meshes,
// collision shapes), limits, transmissions and Gazebo tags are ignored.

#include <fmt/format.h>
#include <tinyxml2.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "elements/links.hpp"
#include "model/bounded_file.hpp"
#include "model/decimal_number.hpp"
#include "model/model_reader.hpp"

namespace lagrange::elements {

namespace {

using tinyxml2::XMLElement;

class UrdfReader {
 public:
  explicit UrdfReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const XMLElement* at, const std::string& message) const {
    throw ModelError(loc(at), message);
  }
  SourceLoc loc(const XMLElement* at) const {
    return SourceLoc{path_, at ? at->GetLineNum() : 0, 0};
  }

  /// A decimal number as an exact rational ("0.089159" → 89159/1000000): no rounded floating
  /// point enters the expressions. URDF numbers are decimal (xs:double without INF and NaN).
  GiNaC::ex decimal(const std::string& text, const XMLElement* at, const std::string& what) const {
    model::Decimal d = model::read_decimal(text);
    if (!d.problem.empty())
      fail(at, fmt::format("{} for {}, got '{}'", d.problem, what, model::clip(text)));
    return d.value;
  }

  /// Three numbers separated by spaces (an attribute; `fallback` when absent).
  Vec3 triple(const XMLElement* e, const char* attr, const Vec3& fallback,
              const std::string& what) const {
    const char* text = e ? e->Attribute(attr) : nullptr;
    if (!text) return fallback;
    std::vector<std::string> parts;
    std::string cur;
    for (const char* p = text;; ++p) {
      if (*p == '\0' || std::isspace(static_cast<unsigned char>(*p))) {
        if (!cur.empty()) parts.push_back(cur);
        cur.clear();
        if (*p == '\0') break;
      } else {
        cur += *p;
      }
    }
    if (parts.size() != 3)
      fail(e, fmt::format("expected three numbers for {}, got '{}'", what, model::clip(text)));
    return {decimal(parts[0], e, what), decimal(parts[1], e, what), decimal(parts[2], e, what)};
  }

  /// An angle: within 1e-9 rad of a multiple of π/2 it is taken as exactly that multiple
  /// (URDFs write 1.57079632679 for π/2), so that the frame's cosines are exact 0 and ±1.
  /// Beyond kMaxAngle a double's spacing exceeds 1e-10 rad and the rotation it names is
  /// rounding noise: such an angle is refused, located, rather than snapped or cast.
  GiNaC::ex angle(const GiNaC::ex& a, const XMLElement* at, const std::string& what) const {
    static constexpr double kMaxAngle = 1e6;  // rad; ulp(1e6) ≈ 1.2e-10
    const double x = GiNaC::ex_to<GiNaC::numeric>(a).to_double();
    if (!(std::abs(x) <= kMaxAngle))
      fail(at, fmt::format("expected an angle of magnitude at most {:g} rad for {}, got {:g}",
                           kMaxAngle, what, x));
    // |k| ≤ kMaxAngle / (π/2) + 1, well inside long's range: the cast below is defined.
    const double k = std::round(x / (M_PI / 2));
    if (std::abs(x - k * M_PI / 2) < 1e-9)
      return GiNaC::numeric(static_cast<long>(k), 2) * GiNaC::Pi;
    return a;
  }
  Vec3 angles(const Vec3& rpy, const XMLElement* at, const std::string& what) const {
    return {angle(rpy[0], at, what), angle(rpy[1], at, what), angle(rpy[2], at, what)};
  }

  std::string name(const XMLElement* e, const char* what) const {
    const char* n = e->Attribute("name");
    if (!n || !*n) fail(e, fmt::format("expected a name for the <{}>", what));
    return n;
  }

  std::string path_;
};

struct Joint {
  const XMLElement* element;
  std::string name, parent, child;
};

/// What tinyxml2 found wrong, in words: "ErrorID=14 (0xe) … XMLElement name=inertial" becomes
/// "the element <inertial> is not closed before its parent's closing tag".
std::string xml_error_words(const tinyxml2::XMLDocument& doc) {
  const std::string raw = doc.ErrorStr() ? doc.ErrorStr() : "";
  std::string subject;  // the element or attribute tinyxml2 names after "Line number=N: "
  const size_t detail = raw.find(": ", raw.find("Line number="));
  if (detail != std::string::npos) {
    const std::string tail = raw.substr(detail + 2);
    for (const char* kind : {"XMLElement name=", "XMLAttribute name=", "XMLText name=",
                             "XMLComment name=", "XMLDeclaration name=", "XMLUnknown name="}) {
      const std::string k = kind;
      if (tail.rfind(k, 0) == 0) subject = tail.substr(k.size());
    }
  }
  const std::string element = subject.empty() ? "an element" : "the element <" + subject + ">";
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return element + " is not closed before its parent's closing tag (a missing </" +
             (subject.empty() ? std::string("…") : subject) + "> or '/>', or a misspelt tag)";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return element + " is malformed or never closed (expected <name …/> or <name …>…</name>)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "a malformed attribute" + (subject.empty() ? "" : " of <" + subject + ">") +
             " (expected name=\"value\" with both quotes)";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "malformed text (a stray '<' or '&'?)";
    case tinyxml2::XML_ERROR_PARSING_CDATA:
      return "an unterminated <![CDATA[ section";
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
      return "an unterminated comment (expected '-->')";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
      return "a malformed <?xml …?> declaration (expected '?>')";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
      return "a malformed <!…> construct";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "an empty file (expected <robot …>)";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
      return "elements nested too deeply";
    case tinyxml2::XML_ERROR_FILE_READ_ERROR:
      return "a file that cannot be read";
    default:
      return "malformed XML (" + raw + ")";
  }
}

}  // namespace

LinkChain read_urdf(const std::string& path) {
  UrdfReader u(path);
  tinyxml2::XMLDocument doc;
  // Read as model files are, up to 16 MiB (issue 37 item 13: a 300 MB file was read whole).
  const std::string text = model::read_bounded_file(path, "URDF file");
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw ModelError(SourceLoc{path, doc.ErrorLineNum(), 0},
                     "expected well-formed XML: " + xml_error_words(doc));
  }
  const XMLElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw ModelError(SourceLoc{path}, "expected a <robot> element at the top");
  std::map<std::string, const XMLElement*> links;
  std::vector<std::string> link_order;
  for (const XMLElement* e = robot->FirstChildElement("link"); e;
       e = e->NextSiblingElement("link")) {
    const std::string n = u.name(e, "link");
    if (!links.emplace(n, e).second)
      u.fail(e, fmt::format("expected each link name once, got '{}' again (first at line {})", n,
                            links[n]->GetLineNum()));
    link_order.push_back(n);
  }
  std::vector<Joint> joints;
  std::map<std::string, size_t> parent_joint;  // child link → joint
  for (const XMLElement* e = robot->FirstChildElement("joint"); e;
       e = e->NextSiblingElement("joint")) {
    Joint j{e, u.name(e, "joint"), "", ""};
    for (const char* end : {"parent", "child"}) {
      const XMLElement* x = e->FirstChildElement(end);
      const char* link = x ? x->Attribute("link") : nullptr;
      if (!link) u.fail(e, fmt::format("expected <{} link=\"…\"/> in joint '{}'", end, j.name));
      if (!links.count(link))
        u.fail(x, fmt::format("expected the name of a <link> for the {} of joint '{}', got '{}' "
                              "(missing link)",
                              end, j.name, model::clip(link)));
      (std::string(end) == "parent" ? j.parent : j.child) = link;
    }
    if (const XMLElement* mimic = e->FirstChildElement("mimic"))
      u.fail(mimic,
             fmt::format("joint '{}' mimics '{}': mimic joints are not supported (give it "
                         "its own coordinate, or couple the joints with a constraint)",
                         j.name, mimic->Attribute("joint") ? mimic->Attribute("joint") : "?"));
    if (parent_joint.count(j.child))
      u.fail(e, fmt::format("link '{}' is the child of joints '{}' and '{}': a URDF is a tree "
                            "(closed chains need constraints)",
                            j.child, joints[parent_joint[j.child]].name, j.name));
    parent_joint[j.child] = joints.size();
    joints.push_back(j);
  }
  std::vector<std::string> roots;
  for (const std::string& n : link_order)
    if (!parent_joint.count(n)) roots.push_back(n);
  if (link_order.empty()) throw ModelError(u.loc(robot), "expected at least one <link>, got none");
  if (roots.empty())
    throw ModelError(u.loc(robot),
                     "the joints form a cycle: every link is some joint's child, "
                     "so there is no root link");
  if (roots.size() > 1)
    u.fail(links[roots[1]], fmt::format("expected one root link, got '{}' and '{}' (links that are "
                                        "no joint's child)",
                                        roots[0], roots[1]));
  LinkChain chain;
  chain.robot = robot->Attribute("name") ? robot->Attribute("name") : "";
  chain.title =
      fmt::format("URDF robot '{}' ({})", robot->Attribute("name") ? robot->Attribute("name") : "?",
                  std::filesystem::path(path).filename().string());
  std::map<std::string, int> index;
  std::vector<std::string> queue{roots[0]};
  for (size_t head = 0; head < queue.size(); ++head) {
    const std::string n = queue[head];  // a copy: queue grows below
    const XMLElement* le = links[n];
    LinkSpec link;
    link.name = n;
    link.loc = u.loc(le);
    link.inertia_loc = link.loc;
    if (parent_joint.count(n)) {
      const Joint& j = joints[parent_joint[n]];
      const XMLElement* e = j.element;
      link.parent = index.at(j.parent);
      const std::string type = e->Attribute("type") ? e->Attribute("type") : "";
      if (type == "revolute" || type == "continuous")
        link.joint.type = JointSpec::Type::Revolute;
      else if (type == "prismatic")
        link.joint.type = JointSpec::Type::Prismatic;
      else if (type == "fixed")
        link.joint.type = JointSpec::Type::Fixed;
      else
        u.fail(e, fmt::format("unsupported joint type '{}' for joint '{}' (supported: revolute, "
                              "continuous, prismatic, fixed)",
                              model::clip(type), j.name));
      link.joint.name = j.name;
      link.joint.loc = u.loc(e);
      const XMLElement* origin = e->FirstChildElement("origin");
      link.joint.xyz =
          u.triple(origin, "xyz", {0, 0, 0}, "the origin xyz of joint '" + j.name + "'");
      const Vec3 rpy =
          u.triple(origin, "rpy", {0, 0, 0}, "the origin rpy of joint '" + j.name + "'");
      link.joint.rpy = u.angles(rpy, origin, "the origin rpy of joint '" + j.name + "'");
      const XMLElement* axis = e->FirstChildElement("axis");
      link.joint.axis = u.triple(axis, "xyz", {1, 0, 0}, "the axis of joint '" + j.name + "'");
      link.joint.axis_loc = u.loc(axis ? axis : e);
      if (const XMLElement* dyn = e->FirstChildElement("dynamics")) {
        if (const char* d = dyn->Attribute("damping")) {
          link.joint.damping = u.decimal(d, dyn, "the damping of joint '" + j.name + "'");
          if (GiNaC::ex_to<GiNaC::numeric>(link.joint.damping).is_negative())
            u.fail(dyn, fmt::format("expected a non-negative damping for joint '{}', got {}",
                                    j.name, d));
        }
        // Coulomb friction (a force discontinuous at q̇ = 0) is not modelled: say so.
        if (const char* f = dyn->Attribute("friction"))
          if (!u.decimal(f, dyn, "the friction of joint '" + j.name + "'").is_zero())
            fmt::print(stderr,
                       "{}: warning: joint '{}' has friction=\"{}\": Coulomb joint friction is "
                       "ignored (damping is applied)\n",
                       u.loc(dyn).str(), j.name, f);
      }
    }
    if (const XMLElement* in = le->FirstChildElement("inertial")) {
      const XMLElement* mass = in->FirstChildElement("mass");
      const char* value = mass ? mass->Attribute("value") : nullptr;
      if (!value)
        u.fail(in, fmt::format("expected <mass value=\"…\"/> in the inertial of link '{}'", n));
      link.mass = u.decimal(value, mass, "the mass of link '" + n + "'");
      if (GiNaC::ex_to<GiNaC::numeric>(link.mass).is_negative())
        u.fail(mass, fmt::format("expected a non-negative mass for link '{}', got {}", n, value));
      const XMLElement* origin = in->FirstChildElement("origin");
      link.com = u.triple(origin, "xyz", {0, 0, 0}, "the inertial origin xyz of link '" + n + "'");
      const Vec3 rpy =
          u.triple(origin, "rpy", {0, 0, 0}, "the inertial origin rpy of link '" + n + "'");
      const XMLElement* inertia = in->FirstChildElement("inertia");
      link.inertia_loc = u.loc(inertia ? inertia : in);
      if (!inertia && !link.mass.is_zero())
        u.fail(in, fmt::format("expected <inertia ixx=\"…\" …/> in the inertial of link '{}'", n));
      Mat3 I{Vec3{0, 0, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 0}};
      const char* names[3][3] = {
          {"ixx", "ixy", "ixz"}, {"ixy", "iyy", "iyz"}, {"ixz", "iyz", "izz"}};
      for (size_t a = 0; a < 3 && inertia; ++a)
        for (size_t b = 0; b < 3; ++b) {
          const char* v = inertia->Attribute(names[a][b]);
          I[a][b] = v ? u.decimal(v, inertia, fmt::format("{} of link '{}'", names[a][b], n))
                      : GiNaC::ex(0);
        }
      // The tensor is given in the inertial frame, rotated by rpy from the link frame.
      const Mat3 R =
          rpy_rotation(u.angles(rpy, origin, "the inertial origin rpy of link '" + n + "'"));
      Mat3 Rt;
      for (size_t a = 0; a < 3; ++a)
        for (size_t b = 0; b < 3; ++b) Rt[a][b] = R[b][a];
      link.inertia = mat_mul(mat_mul(R, I), Rt);
      for (auto& row : link.inertia)
        for (auto& x : row) x = x.expand();
    }
    index[n] = static_cast<int>(chain.links.size());
    chain.links.push_back(std::move(link));
    for (const Joint& j : joints)
      if (j.parent == n) queue.push_back(j.child);
  }
  if (queue.size() < link_order.size()) {
    std::set<std::string> reached(queue.begin(), queue.end());
    for (const Joint& j : joints)
      if (!reached.count(j.child))
        u.fail(j.element, fmt::format("the joints form a cycle through joint '{}' (link '{}' is "
                                      "not reachable from the root link '{}')",
                                      j.name, j.child, roots[0]));
  }
  return chain;
}

// `urdf: file.urdf` or `urdf: {file, initial: {joint: q0}, rate: {joint: v0}}` in a model file.
void declare_urdf(model::ModelReader& r, const YAML::Node& node, LinkChain& chain) {
  // YAML::Node assignment writes through to the node referred to: reset() rebinds instead.
  YAML::Node file, initial, rate;
  file.reset(node);
  if (node.IsMap()) {
    r.check_keys(node, {"file", "initial", "rate"}, "urdf");
    if (!node["file"]) r.fail(node, "expected 'file' (the URDF file) in urdf, got none");
    file.reset(node["file"]);
    // an absent key gives an invalid node, which reset() refuses (issue 25 item 6)
    if (node["initial"]) initial.reset(node["initial"]);
    if (node["rate"]) rate.reset(node["rate"]);
  }
  const std::string name = r.scalar(file, "URDF file");
  if (name.empty()) r.fail(file, "expected the name of a URDF file in urdf, got ''");
  std::filesystem::path p = name;
  if (p.is_relative()) p = std::filesystem::path(r.source().file()).parent_path() / p;
  // A file named in a model file that cannot be opened is the model file's mistake, at its line.
  std::error_code ec;
  if (std::filesystem::path(r.source().file()).extension() != ".urdf" &&
      !std::filesystem::is_regular_file(p, ec))
    r.fail(file,
           fmt::format("cannot open the URDF file '{}': {}", model::clip(p.string(), 200),
                       std::filesystem::exists(p, ec) ? "not a regular file" : "no such file"));
  // One too large is too, before it is read (issue 37 item 13).
  if (const auto bytes = std::filesystem::file_size(p, ec);
      !ec && bytes > model::kMaxModelBytes &&
      std::filesystem::path(r.source().file()).extension() != ".urdf")
    r.fail(file, fmt::format("expected a URDF file of at most {} MiB, got '{}' of {:.1f} MiB",
                             model::kMaxModelBytes >> 20, model::clip(p.string(), 200),
                             static_cast<double>(bytes) / (1 << 20)));
  chain = read_urdf(p.lexically_normal().string());
  // A URDF given on its own (model/yaml_reader.cpp) is named after its <robot name>.
  if (std::filesystem::path(r.source().file()).extension() == ".urdf" && !chain.robot.empty())
    r.model().name = chain.robot;
  for (const auto& [values, what] : {std::pair{initial, "initial"}, std::pair{rate, "rate"}}) {
    if (!values || values.IsNull()) continue;
    r.expect_map(values, fmt::format("urdf {} (a map joint: value)", what));
    for (const auto& kv : values) {
      LinkSpec* found = nullptr;
      for (LinkSpec& l : chain.links)
        if (l.parent >= 0 && l.joint.type != JointSpec::Type::Fixed &&
            l.joint.name == kv.first.Scalar())
          found = &l;
      if (!found)
        r.fail(kv.first, fmt::format("expected a movable joint of the URDF for its {}, got '{}'",
                                     what, model::clip(kv.first.Scalar())));
      const double v = r.number(kv.second, model::kParams,
                                fmt::format("{} of joint {}", what, kv.first.Scalar()));
      (std::string(what) == "initial" ? found->joint.initial : found->joint.rate) = v;
      if (std::string(what) == "initial" && found->joint.type == JointSpec::Type::Revolute)
        r.warn_implausible(v, kv.second, model::ModelReader::Quantity::Angle,
                           "the initial angle of joint '" + found->joint.name + "'");
    }
  }
  declare_chain(r, chain);
}

}  // namespace lagrange::elements
