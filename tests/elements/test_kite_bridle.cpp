// Bridles (src/elements/bridle.cpp): three lines of equal length hold the knot at one point of
// the kite, so the bridled kite flies as the kite tethered at that point.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "support/harness.hpp"

namespace lagrange {
namespace {

std::string example_text(const std::string& name) {
  std::ifstream in(testing::example_path(name));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

/// bridled_kite.yaml with the tether at body point [0, 0, 0.5] instead of the bridle's knot.
std::string single_point_model() {
  std::string text = example_text("bridled_kite.yaml");
  const size_t from = text.find("bridles:\n"), to = text.find("tethers:\n");
  EXPECT_TRUE(from != std::string::npos && to != std::string::npos);
  text.erase(from, to - from);
  replace(text, "      front: [1.2, 0, 0]\n", "      attach: [0, 0, 0.5]\n");
  replace(text, "bridle.knot", "plane.attach");
  return text;
}

Trajectory run(testing::Loaded& sys, double rtol) {
  SimulationOptions so = testing::tight(sys, 10, 0.05);
  so.integrator.rtol = rtol;
  so.integrator.atol = rtol * 1e-2;
  return sys.run(so);
}

double max_difference(const Trajectory& a, const Trajectory& b) {
  double d = 0;
  for (size_t r = 0; r < std::min(a.rows(), b.rows()); ++r)
    for (const char* col : {"plane.x", "plane.y", "plane.z"})
      d = std::max(d, std::abs(a.at(r, col) - b.at(r, col)));
  return d;
}

// The knot x_k meets three lines of length ℓ from body points p_i equidistant from the body
// point k_b = [0, 0, 0.5]; x_k = r + R k_b satisfies all three, and since the lines' directions
// are independent, it is the only solution near the start. Both models then have the same
// configuration space, the same kinetic energy (the tether's end mass sits at x_k in both; the
// lines carry none), the same potential and the same forces: their equations of motion on the
// manifold are identical. What separates the two runs is numerical: the knot's offset from
// r + R k_b, |δ| ≤ |ΔC|/σ_min(J) with J the lines' Jacobian (rows x_k − p_i, σ_min ≈ 0.6 m here)
// and ΔC the constraint residual (≤ 1e-10 m² after projection), and each run's integration
// error, samples' interpolation included. Each run's error at rtol ε is estimated by its
// difference from the same model at ε/10 (about ten times more accurate, so the estimate is good
// to about 10 %): the two runs at ε differ by at most the sum of their errors, plus 1e-9 m for
// the knot offset; the bar takes 1.5 × the estimates.
TEST(BridledKite, EqualLinesFlyAsTheSinglePointAttachmentAtTheKnot) {
  auto bridled = testing::load_example("bridled_kite.yaml");
  auto single = testing::load_string(single_point_model());
  const double eps = 1e-11;
  const Trajectory tb = run(bridled, eps), ts = run(single, eps);
  const Trajectory tb_tight = run(bridled, eps / 10), ts_tight = run(single, eps / 10);
  for (const Trajectory* tr : {&tb, &ts, &tb_tight, &ts_tight})
    ASSERT_EQ(tr->status, Trajectory::Status::Complete) << tr->message;
  ASSERT_EQ(tb.rows(), ts.rows());
  const double error_b = max_difference(tb, tb_tight), error_s = max_difference(ts, ts_tight);
  const double gap = max_difference(tb, ts);
  double sweep = 0;  // it flies across the wind
  for (size_t r = 0; r < tb.rows(); ++r) sweep = std::max(sweep, std::abs(tb.at(r, "plane.y")));
  EXPECT_GT(sweep, 50.0);
  double reach = 0;
  for (size_t r = 0; r < ts.rows(); ++r)
    for (const char* col : {"plane.x", "plane.y", "plane.z"})
      reach = std::max(reach, std::abs(ts.at(r, col)));
  EXPECT_LT(gap, 1.5 * (error_b + error_s) + 1e-9)
      << "estimated errors " << error_b << " (bridled), " << error_s << " (single point)";
  EXPECT_LT(error_b + error_s, 1e-9 * reach) << "rtol 1e-11, over a flight of 10 s";
  double tension = 0, offset = 0;
  for (size_t r = 0; r < tb.rows(); ++r) {
    tension = std::max(tension,
                       std::abs(tb.at(r, "main.tension_ground") - ts.at(r, "main.tension_ground")));
    const Eigen::Matrix3d R = testing::rotation_at(tb, r, "plane");
    const Eigen::Vector3d knot{tb.at(r, "bridle.knot.x"), tb.at(r, "bridle.knot.y"),
                               tb.at(r, "bridle.knot.z")};
    const Eigen::Vector3d body{tb.at(r, "plane.x"), tb.at(r, "plane.y"), tb.at(r, "plane.z")};
    offset = std::max(offset, (knot - body - R * Eigen::Vector3d(0, 0, 0.5)).norm());
  }
  EXPECT_LT(offset, 1e-9);
  EXPECT_LT(tension, 1e-3);  // N, of kilonewtons
}

// The lines pull on the knot (positive tensions, λᵢℓᵢ) throughout the flight.
TEST(BridledKite, LineTensionsStayPositive) {
  auto sys = testing::load_example("bridled_kite.yaml");
  const Trajectory tr = run(sys, 1e-10);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 0; r < tr.rows(); ++r)
    for (const char* col : {"bridle.tension_1", "bridle.tension_2", "bridle.tension_3"})
      EXPECT_GT(tr.at(r, col), 100.0) << col << " at t = " << tr.at(r, "t");
}

}  // namespace
}  // namespace lagrange
