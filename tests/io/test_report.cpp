// The report's scene JSON (src/io/report_scene.cpp): positions match the trajectory, rotations
// are orthonormal, links come from the motion, decimation keeps the ends, and the visual
// section's mistakes are model errors with a location.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lagrange/io.hpp"
#include "lagrange/report.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

struct SceneRun {
  testing::Loaded sys;
  Equations eq;
  Trajectory traj;
  nlohmann::json scene;
};

SceneRun run_example(const std::string& name, double t_end, const ReportLimits& limits = {}) {
  SceneRun r{testing::load_example(name), {}, {}, {}};
  r.eq = derive(*r.sys.model);
  SimulationOptions so = r.sys.options();
  so.t_end = t_end;
  r.traj = r.sys.run(so);
  r.scene = nlohmann::json::parse(
      report_scene_json(r.eq, *r.sys.compiled, r.traj, r.sys.dynamics->parameters(), limits));
  return r;
}

size_t point_index(const nlohmann::json& scene, const std::string& name) {
  for (size_t i = 0; i < scene["points"].size(); ++i)
    if (scene["points"][i]["name"] == name) return i;
  ADD_FAILURE() << "no point " << name;
  return 0;
}

// The row of the trajectory at time t (frames are trajectory rows).
size_t row_at(const Trajectory& traj, double t) {
  size_t best = 0;
  for (size_t r = 0; r < traj.rows(); ++r)
    if (std::abs(traj.at(r, "t") - t) < std::abs(traj.at(best, "t") - t)) best = r;
  EXPECT_NEAR(traj.at(best, "t"), t, 1e-12);
  return best;
}

TEST(ReportScene, PositionsMatchTheTrajectoryAtEveryFrame) {
  const SceneRun r = run_example("double_pendulum.yaml", 2.0);
  const auto& s = r.scene;
  const size_t np = s["points"].size(), p2 = point_index(s, "p2");
  ASSERT_GT(s["t"].size(), 10u);
  const double tol = 2e-4 * s["extent"].get<double>();
  for (size_t f = 0; f < s["t"].size(); ++f) {
    const size_t row = row_at(r.traj, s["t"][f]);
    EXPECT_NEAR(s["positions"][3 * (f * np + p2)].get<double>(), r.traj.at(row, "x2"), tol);
    EXPECT_NEAR(s["positions"][3 * (f * np + p2) + 1].get<double>(), r.traj.at(row, "y2"), tol);
    EXPECT_NEAR(s["positions"][3 * (f * np + p2) + 2].get<double>(), 0.0, tol);
  }
  // A planar model in the x-y plane with gravity along -y: seen along z, y up.
  EXPECT_EQ(s["normal"], nlohmann::json({0, 0, 1}));
  EXPECT_EQ(s["up"], nlohmann::json({0.0, 1.0, 0.0}));
  // Equal masses: equal spheres; the tip's path is the trail.
  EXPECT_EQ(s["points"][p2]["kind"], "particle");
  EXPECT_EQ(s["trail"], nlohmann::json({p2}));
}

TEST(ReportScene, LinksAreTheConstantDistancesOfTheMotion) {
  const SceneRun r = run_example("double_pendulum.yaml", 2.0);
  const auto& s = r.scene;
  const size_t p1 = point_index(s, "p1"), p2 = point_index(s, "p2");
  std::set<std::pair<size_t, size_t>> links;
  for (const auto& g : s["segments"]) {
    EXPECT_EQ(g["kind"], "link");
    const size_t a = g["a"], b = g["b"];
    links.insert({std::min(a, b), std::max(a, b)});
  }
  // pivot (an anchor at the origin, the ground part of p1) – p1 – p2; never pivot – p2.
  ASSERT_EQ(links.size(), 2u);
  EXPECT_TRUE(links.count({std::min(p1, p2), std::max(p1, p2)}));
  const size_t anchor = s["points"].size() - 1;
  EXPECT_EQ(s["points"][anchor]["kind"], "anchor");
  EXPECT_TRUE(links.count({p1, anchor}));
  const size_t nf = s["t"].size(), np = s["points"].size();
  for (size_t f = 0; f < nf; f += nf / 5)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s["positions"][3 * (f * np + anchor) + k], 0.0);
}

TEST(ReportScene, FiveBarGroundPivotsAreFoundFromThePointExpressions) {
  const SceneRun r = run_example("five_bar.yaml", 1.0);
  const auto& s = r.scene;
  const size_t np = s["points"].size();
  // Anchors at the two ground pivots (0, 0, 0) and (d, 0, 0) = (1.2, 0, 0).
  std::vector<double> xs;
  for (size_t i = 0; i < np; ++i)
    if (s["points"][i]["kind"] == "anchor") xs.push_back(s["positions"][3 * i]);
  std::sort(xs.begin(), xs.end());
  ASSERT_EQ(xs.size(), 2u);
  EXPECT_NEAR(xs[0], 0.0, 1e-12);
  EXPECT_NEAR(xs[1], 1.2, 1e-12);
  // The cranks B and D on their pivots, the couplers B-C and D-C2; C and C2 coincide (the loop
  // closure), so each coupler also shows as a link to the other's pin: six links in all.
  std::set<std::pair<size_t, size_t>> links;
  for (const auto& g : s["segments"]) {
    EXPECT_EQ(g["kind"], "link");
    links.insert({g["a"].get<size_t>(), g["b"].get<size_t>()});
  }
  const size_t B = point_index(s, "B"), C = point_index(s, "C"), D = point_index(s, "D"),
               C2 = point_index(s, "C2");
  auto linked = [&](size_t a, size_t b) { return links.count({a, b}) + links.count({b, a}) > 0; };
  EXPECT_TRUE(linked(B, C) && linked(D, C2) && linked(B, C2) && linked(D, C))
      << s["segments"].dump();
  EXPECT_FALSE(linked(B, D));
  EXPECT_EQ(links.size(), 6u) << s["segments"].dump();
}

TEST(ReportScene, BodyRotationsAreOrthonormalAndTheShapeIsTheBox) {
  const SceneRun r = run_example("tumbling_brick.yaml", 4.0);
  const auto& s = r.scene;
  ASSERT_EQ(s["bodies"].size(), 1u);
  const auto& b = s["bodies"][0];
  EXPECT_EQ(b["shape"], "box");
  // The box of edges a, b, c = 0.3, 0.2, 0.1 from its inertia.
  std::vector<double> size = b["size"];
  std::sort(size.begin(), size.end());
  EXPECT_NEAR(size[0], 0.1, 1e-9);
  EXPECT_NEAR(size[1], 0.2, 1e-9);
  EXPECT_NEAR(size[2], 0.3, 1e-9);
  const size_t nf = s["t"].size();
  double worst = 0, turned = 0;
  for (size_t f = 0; f < nf; ++f) {
    Eigen::Matrix3d R;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R(i, j) = s["poses"][12 * f + 3 + 3 * i + j];
    worst = std::max(worst, (R.transpose() * R - Eigen::Matrix3d::Identity()).norm());
    EXPECT_NEAR(R.determinant(), 1.0, 1e-4);
    const Eigen::Matrix3d exact = testing::rotation_at(r.traj, row_at(r.traj, s["t"][f]), "brick");
    EXPECT_LT((R - exact).norm(), 1e-4);
    turned = std::max(turned, (R - Eigen::Matrix3d::Identity()).norm());
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(turned, 1.0) << "the brick spins";
  EXPECT_TRUE(s["normal"].is_null()) << "a tumbling brick is not planar";
}

TEST(ReportScene, PlanarLinksAreCapsulesFromTheJointThroughTheCentreOfMass) {
  // inertia [0, 0, I]: no solid has it; the upper arm's centre of mass is at Lc1 = 0.5 along x.
  const SceneRun r = run_example("elbow_manipulator.yaml", 0.5);
  const auto& bodies = r.scene["bodies"];
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0]["name"], "upper");
  EXPECT_EQ(bodies[0]["shape"], "capsule");
  EXPECT_NEAR(bodies[0]["size"][2].get<double>(), 1.0, 1e-12);  // 2 Lc1 = L1: joint to joint
  EXPECT_EQ(bodies[0]["center"], nlohmann::json({0.5, 0.0, 0.0}));
  // The capsule's axis (third column of `axes`) runs along body x.
  EXPECT_NEAR(bodies[0]["axes"][2].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(bodies[1]["size"][2].get<double>(), 0.8, 1e-12);  // 2 Lc2
}

TEST(ReportScene, DecimationKeepsTheFirstAndLastSampleWithinTheLimits) {
  ReportLimits limits;
  limits.max_frames = 50;
  const SceneRun r = run_example("pendulum.yaml", 3.0, limits);
  const auto& t = r.scene["t"];
  ASSERT_EQ(t.size(), 50u);
  EXPECT_EQ(t.front().get<double>(), r.traj.at(0, "t"));
  EXPECT_EQ(t.back().get<double>(), r.traj.at(r.traj.rows() - 1, "t"));
  for (size_t f = 1; f < t.size(); ++f) EXPECT_GT(t[f].get<double>(), t[f - 1].get<double>());
  limits.max_frames = 100000;
  limits.max_scene_numbers = 150;  // one point, the bob: 3 numbers a frame
  const SceneRun small = run_example("pendulum.yaml", 3.0, limits);
  EXPECT_EQ(small.scene["t"].size(), 50u);
}

TEST(ReportScene, TetherNodesAreLinkedInAChainAndFixedEndsShown) {
  const SceneRun r = run_example("crane_with_cable.yaml", 1.0);
  const auto& s = r.scene;
  size_t links = 0;
  for (const auto& g : s["segments"]) links += g["kind"] == "link" || g["kind"] == "spring";
  EXPECT_GE(links, 20u) << s["segments"].dump();  // one per cable segment at least
  EXPECT_EQ(s["up"], nlohmann::json({0.0, 0.0, 1.0}));
}

fs::path scratch_model(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("lagrange-report-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

const char* kPendulum = R"(name: visual pendulum
parameters: {m: 1.0, l: 1.0, g: 9.81}
coordinates:
  theta: {initial: 1.0}
points:
  bob: [l*sin(theta), -l*cos(theta), 0]
  mid: [l/2*sin(theta), -l/2*cos(theta), 0]
particles: {bob: m}
gravity: [0, -g, 0]
simulate: {t_end: 1, output_step: 0.01}
)";

nlohmann::json scene_of(const fs::path& file) {
  auto sys = testing::load_model(std::make_unique<Model>(read_model_file(file.string())));
  const Equations eq = derive(*sys.model);
  const Trajectory traj = sys.run(sys.options());
  return nlohmann::json::parse(
      report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
}

TEST(ReportVisual, ColoursSizesTrailsAndHiddenPoints) {
  const auto file = scratch_model("visual.yaml", std::string(kPendulum) + R"(visual:
  color: {bob: '#123456'}
  size: {bob: 0.25}
  trail: [mid]
  hide: [mid]
)");
  const auto s = scene_of(file);
  ASSERT_EQ(s["points"][0]["name"], "bob");
  EXPECT_EQ(s["points"][0]["color"], "#123456");
  EXPECT_EQ(s["points"][0]["radius"], 0.25);
  for (const auto& p : s["points"]) EXPECT_NE(p["name"], "mid");
  EXPECT_EQ(s["trail"], nlohmann::json::array()) << "a hidden point leaves no trail";
}

TEST(ReportVisual, AModelReadFromTextIsDrawnAsItsVisualSectionSays) {
  // One parser: the report draws from the reader's Model::visual, so a model with no file to read
  // again (the Python module's loads()) keeps its colours, sizes and trails.
  const std::string text = std::string(kPendulum) + R"(visual:
  color: {bob: DarkRed, mid: '#0a0'}
  size: {mid: 0.05}
  trail: [mid]
)";
  auto sys = testing::load_model(std::make_unique<Model>(read_model_string(text, "<text>")));
  const Equations eq = derive(*sys.model);
  const Trajectory traj = sys.run(sys.options());
  const auto s =
      nlohmann::json::parse(report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
  const size_t bob = point_index(s, "bob"), mid = point_index(s, "mid");
  EXPECT_EQ(s["points"][bob]["color"], "DarkRed");
  EXPECT_EQ(s["points"][mid]["color"], "#0a0");
  EXPECT_EQ(s["points"][mid]["radius"], 0.05);
  EXPECT_EQ(s["trail"], nlohmann::json::array({mid})) << "the trail written, not the default bob";
}

TEST(ReportVisual, MistakesNameTheLineAndWhatWasExpected) {
  const auto unknown = scratch_model("unknown.yaml", std::string(kPendulum) + R"(visual:
  color: {nope: red}
)");
  try {
    scene_of(unknown);
    FAIL() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().line, 12);
    EXPECT_EQ(e.loc().column, 11);
    EXPECT_NE(
        std::string(e.what()).find("expected a point, body or element name in visual, got 'nope'"),
        std::string::npos)
        << e.what();
  }
  const auto colour = scratch_model("colour.yaml", std::string(kPendulum) + R"(visual:
  color: {bob: 'rgb(1,2,3)'}
)");
  EXPECT_THROW(scene_of(colour), ModelError);
  const auto key =
      scratch_model("key.yaml", std::string(kPendulum) + "visual: {colour: {bob: red}}\n");
  EXPECT_THROW(scene_of(key), ModelError);
}

TEST(ReportCsv, ReadsBackWhatSimulateWrote) {
  auto sys = testing::load_example("cartesian_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 0.3;
  const Trajectory tr = sys.run(so);
  const auto path = scratch_model("traj.csv", "");
  write_trajectory_csv(tr, path.string());
  const Trajectory back = read_trajectory_csv(path.string());
  EXPECT_EQ(back.columns, tr.columns);
  EXPECT_EQ(back.data, tr.data);
  EXPECT_EQ(back.stats.steps, tr.stats.steps);
  std::ofstream(path) << "t,x\n0,1\n0.1\n";
  try {
    read_trajectory_csv(path.string());
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":3: expected 2 values, got 1"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lagrange
