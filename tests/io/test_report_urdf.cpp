// URDF <visual> geometry in the report's scene (src/io/report_urdf.cpp, issue 36 item 13): the
// shapes, origins, rpy rotations, colours and embedded meshes of tests/io/urdf_visuals/, mesh
// files found through package://, and the inertia drawing kept, with a note, where a mesh is
// missing.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "hardening/cli_runner.hpp"
#include "io/report_urdf.hpp"
#include "lagrange/io.hpp"
#include "lagrange/report.hpp"
#include "support/file_text.hpp"
#include "support/harness.hpp"
#include "support/test_paths.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

fs::path arm_dir() {
  return fs::path(LAGRANGE_SOURCE_DIR) / "tests" / "io" / "urdf_visuals";
}

nlohmann::json urdf_scene(const fs::path& urdf) {
  auto sys = testing::load_model(std::make_unique<Model>(read_model_file(urdf.string())));
  SimulationOptions so = sys.options();
  so.t_end = 0.2;
  const Equations eq = derive(*sys.model);
  const Trajectory traj = sys.run(so);
  EXPECT_EQ(traj.status, Trajectory::Status::Complete);
  return nlohmann::json::parse(
      report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
}

const nlohmann::json& body(const nlohmann::json& scene, const std::string& name) {
  for (const auto& b : scene["bodies"])
    if (b["name"] == name) return b;
  ADD_FAILURE() << "no body " << name;
  return scene["bodies"][0];
}

void expect_near(const nlohmann::json& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size()) << got;
  for (size_t k = 0; k < want.size(); ++k) EXPECT_NEAR(got[k].get<double>(), want[k], 1e-12) << k;
}

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(ReportUrdf, EveryVisualOfTheArmIsInTheScene) {
  const ScopedEnv no_packages("ROS_PACKAGE_PATH", "");
  const nlohmann::json scene = urdf_scene(arm_dir() / "visual_arm.urdf");
  EXPECT_FALSE(scene.contains("notes")) << scene["notes"];
  const std::string stl = test::slurp(arm_dir() / "meshes" / "tip.stl");
  const std::string dae = test::slurp(arm_dir() / "meshes" / "plate.dae");
  EXPECT_EQ(scene["mesh_bytes"], stl.size() + dae.size());

  const auto& base = body(scene, "base")["visuals"];
  ASSERT_EQ(base.size(), 2u);
  EXPECT_EQ(base[0]["type"], "cylinder");
  EXPECT_EQ(base[0]["radius"], 0.05);
  EXPECT_EQ(base[0]["length"], 0.1);
  EXPECT_EQ(base[0]["color"], "#0000ff");  // the robot's named material "blue"
  EXPECT_EQ(base[0]["opacity"], 1.0);
  EXPECT_EQ(base[1]["type"], "mesh");  // a path relative to the URDF's folder
  EXPECT_EQ(base[1]["format"], "dae");
  EXPECT_EQ(base[1]["data"], io::base64(dae));
  expect_near(base[1]["origin"], {0, 0, -0.05});
  expect_near(base[1]["scale"], {1, 1, 1});

  const auto& upper = body(scene, "upper")["visuals"];
  ASSERT_EQ(upper.size(), 2u);
  EXPECT_EQ(upper[0]["type"], "box");
  expect_near(upper[0]["size"], {0.04, 0.04, 0.5});
  expect_near(upper[0]["origin"], {0, 0, 0.25});
  EXPECT_EQ(upper[0]["color"], "#ff0000");
  EXPECT_EQ(upper[0]["opacity"], 0.5);
  EXPECT_EQ(upper[1]["type"], "sphere");
  EXPECT_EQ(upper[1]["radius"], 0.03);
  expect_near(upper[1]["origin"], {0, 0, 0.5});
  expect_near(upper[1]["rotation"], {1, 0, 0, 0, 1, 0, 0, 0, 1});
  EXPECT_FALSE(upper[1].contains("color"));

  // The STL, found through package://urdf_visuals/ (the URDF's own folder), embedded whole; rpy
  // (0, π/2, 0) is Ry(π/2), which turns x onto −z.
  const auto& tool = body(scene, "tool")["visuals"];
  ASSERT_EQ(tool.size(), 1u);
  EXPECT_EQ(tool[0]["type"], "mesh");
  EXPECT_EQ(tool[0]["format"], "stl");
  EXPECT_EQ(tool[0]["data"], io::base64(stl));
  expect_near(tool[0]["scale"], {2, 2, 2});
  expect_near(tool[0]["origin"], {0.1, 0, 0});
  const auto& r = tool[0]["rotation"];
  const double want[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};
  for (size_t k = 0; k < 9; ++k) EXPECT_NEAR(r[k].get<double>(), want[k], 1e-15) << k;
}

TEST(ReportUrdf, AMissingMeshKeepsTheInertiaDrawingWithANote) {
  const ScopedEnv no_packages("ROS_PACKAGE_PATH", "");
  const fs::path dir = fs::temp_directory_path() / ("lagrange-urdf-" + std::to_string(getpid()));
  fs::create_directories(dir);
  fs::copy_file(arm_dir() / "visual_arm.urdf", dir / "visual_arm.urdf",
                fs::copy_options::overwrite_existing);
  const nlohmann::json scene = urdf_scene(dir / "visual_arm.urdf");
  fs::remove_all(dir);
  ASSERT_EQ(scene["notes"].size(), 2u);  // the plate of 'base', the tip of 'tool'
  EXPECT_NE(scene["notes"][0].get<std::string>().find("link 'base': mesh 'meshes/plate.dae'"),
            std::string::npos)
      << scene["notes"][0];
  const std::string note = scene["notes"][1];
  EXPECT_NE(note.find("link 'tool'"), std::string::npos) << note;
  EXPECT_NE(note.find("package://urdf_visuals/meshes/tip.stl' not found"), std::string::npos)
      << note;
  EXPECT_FALSE(body(scene, "tool").contains("visuals"));
  EXPECT_TRUE(body(scene, "tool").contains("shape"));  // today's drawing
  EXPECT_FALSE(body(scene, "base").contains("visuals"));
  EXPECT_TRUE(body(scene, "upper").contains("visuals"));
  EXPECT_FALSE(scene.contains("mesh_bytes"));
}

TEST(ReportUrdf, ARobotWithoutVisualsAndAYamlModelHaveNone) {
  for (const char* name : {"robots/panda.urdf", "double_pendulum.yaml"}) {
    auto sys = testing::load_example(name);
    SimulationOptions so = sys.options();
    so.t_end = 0.05;
    const Equations eq = derive(*sys.model);
    const Trajectory traj = sys.run(so);
    const auto scene = nlohmann::json::parse(
        report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
    EXPECT_FALSE(scene.contains("notes")) << name;
    for (const auto& b : scene["bodies"]) EXPECT_FALSE(b.contains("visuals")) << name;
  }
}

TEST(ReportUrdf, MeshFilesAreFoundAsRosFindsThem) {
  const fs::path urdf = arm_dir() / "visual_arm.urdf";
  const std::string tip = (arm_dir() / "meshes" / "tip.stl").lexically_normal().string();
  {
    const ScopedEnv none("ROS_PACKAGE_PATH", "");
    EXPECT_EQ(io::resolve_mesh("meshes/tip.stl", urdf.string()), tip);
    EXPECT_EQ(io::resolve_mesh("file://" + tip, urdf.string()), tip);
    EXPECT_EQ(io::resolve_mesh("package://urdf_visuals/meshes/tip.stl", urdf.string()), tip);
    EXPECT_EQ(io::resolve_mesh("package://io/urdf_visuals/meshes/tip.stl", urdf.string()), tip);
    EXPECT_EQ(io::resolve_mesh("package://other/meshes/tip.stl", urdf.string()), "");
    EXPECT_EQ(io::resolve_mesh("meshes/none.stl", urdf.string()), "");
  }
  // A package elsewhere: its folder in $ROS_PACKAGE_PATH.
  const ScopedEnv path("ROS_PACKAGE_PATH", "/nonexistent:" + arm_dir().parent_path().string());
  EXPECT_EQ(io::resolve_mesh("package://urdf_visuals/meshes/tip.stl", "/elsewhere/robot.urdf"),
            tip);
}

// The scene embedded in a report file.
nlohmann::json report_scene(const fs::path& html) {
  const std::string text = hardening::slurp(html);
  const std::string open = "id=\"lagrange-data\">";
  const size_t from = text.find(open) + open.size();
  return nlohmann::json::parse(text.substr(from, text.find("</script>", from) - from))["scene"];
}

TEST(ReportUrdf, PackagePathFindsTheMeshesOfAUrdfElsewhere) {
  const ScopedEnv none("ROS_PACKAGE_PATH", "");
  hardening::ScratchDir dir("report-package-path");
  fs::copy_file(arm_dir() / "visual_arm.urdf", dir.path() / "visual_arm.urdf");
  const std::string urdf = (dir.path() / "visual_arm.urdf").string();
  const auto html = dir.path() / "arm.html";
  const std::vector<std::string> run{"simulate", urdf, "--t-end", "0.2", "--report", html.string()};
  const hardening::RunResult without = hardening::run_lagrange(dir.path(), run);
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_EQ(report_scene(html)["notes"].size(), 2u);
  // The notes also on stderr, once each.
  EXPECT_NE(without.err.find("lagrange: note: link 'tool': mesh "
                             "'package://urdf_visuals/meshes/tip.stl' not found"),
            std::string::npos)
      << without.err;
  EXPECT_EQ(without.out.find("of URDF meshes"), std::string::npos) << without.out;
  EXPECT_FALSE(body(report_scene(html), "tool").contains("visuals"));
  // tests/io holds the package urdf_visuals/.
  std::vector<std::string> with = run;
  with.insert(with.end(), {"--package-path", "/nonexistent", "--package-path",
                           arm_dir().parent_path().string()});
  const hardening::RunResult r = hardening::run_lagrange(dir.path(), with);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(html.string() + " embeds 0.3 KiB of URDF meshes"), std::string::npos)
      << r.out;  // the 284-byte STL
  const nlohmann::json scene = report_scene(html);
  // The plate, named relative to the URDF's folder, is still missing there.
  ASSERT_EQ(scene["notes"].size(), 1u);
  EXPECT_NE(scene["notes"][0].get<std::string>().find("link 'base'"), std::string::npos);
  ASSERT_TRUE(body(scene, "tool").contains("visuals"));
  EXPECT_EQ(body(scene, "tool")["visuals"][0]["type"], "mesh");
}

TEST(ReportUrdf, Base64) {
  EXPECT_EQ(io::base64(""), "");
  EXPECT_EQ(io::base64("f"), "Zg==");
  EXPECT_EQ(io::base64("fo"), "Zm8=");
  EXPECT_EQ(io::base64("foo"), "Zm9v");
  EXPECT_EQ(io::base64("foob"), "Zm9vYg==");
  EXPECT_EQ(io::base64(std::string("\0\xff\x10", 3)), "AP8Q");
}

}  // namespace
}  // namespace lagrange
