// Load columns (docs/theory.md §4.11): the winch drum's `<winch>.load` and a fixed anchor's
// `<tether>.load_ground` read what a load cell there reads, unlike the first segment's tension.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "hardening/cli_runner.hpp"
#include "support/harness.hpp"
#include "support/winch_with_payload.hpp"

namespace lagrange::testing {
namespace {

namespace wp = winch_payload;
namespace fs = std::filesystem;

// Below the drum hangs the straight line with its payload: (μℓ + m_p)(g − ℓ̈) pulls on the drum.
double hanging_pull(double ell, double acceleration) {
  return (wp::kMp + wp::kMu * ell) * (wp::kG - acceleration);
}

TEST(Loads, DrumLoadUnderAMotorTorqueIsTheHangingLinesWeightLessItsInertia) {
  for (const int n : {2, 6, 24}) {
    Loaded sys = load_string(wp::model(n));
    const Trajectory tr = sys.run(tight(sys, 4, 0.05));
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    for (size_t r = 0; r < tr.rows(); ++r) {
      const double ell = tr.at(r, "drum.reeled_out");
      const double expected = hanging_pull(ell, wp::acceleration(ell));
      ASSERT_NEAR(tr.at(r, "drum.load"), expected, 1e-8 * expected) << "N = " << n << ", row " << r;
    }
    // At the start (ℓ̇ = 0.5 m/s) the first segment's tension misses about the mass lumped at
    // the drum's node, m₀ (g − ℓ̈) with m₀ = μℓ/(N + 1): a share that shrinks as 1/N. (Reeling
    // faster, the segment tensions of a reeling line also carry a term of order μℓ̇² from the
    // material-velocity model, docs/theory.md §4.11; the load column has neither.)
    const double node_share = wp::kMu * wp::kEll0 / (n + 1) / (wp::kMp + wp::kMu * wp::kEll0);
    const double share = 1 - tr.at(0, "line.tension_ground") / tr.at(0, "drum.load");
    if (n > 6) continue;  // at N = 24 the node's share (0.7 %) is as small as that term
    EXPECT_GT(share, 0.5 * node_share) << "N = " << n;
    EXPECT_LT(share, 1.5 * node_share) << "N = " << n;
  }
}

TEST(Loads, DrumLoadUnderAPrescribedReelOutCarriesTheReelsForce) {
  Loaded sys = load_string(wp::model(6, "reeled_out: 1 + 0.5*t + 0.3*t^2"));
  const Trajectory tr = sys.run(tight(sys, 2, 0.05));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 0; r < tr.rows(); ++r) {
    const double t = tr.at(r, "t"), ell = 1 + 0.5 * t + 0.3 * t * t;
    const double expected = hanging_pull(ell, 0.6);
    ASSERT_NEAR(tr.at(r, "drum.load"), expected, 1e-8 * expected) << "t = " << t;
  }
}

// Issue 20, item 4, as a user meets it: `simulate` writes the drum's load beside the first
// segment's tension, and the load is the closed form's (μℓ + m_p)(g − ℓ̈) at every sample.
TEST(Loads, SimulateWritesTheDrumLoadColumn) {
  hardening::ScratchDir dir("loads-" + std::to_string(::getpid()));
  hardening::spit(dir.path() / "winch.yaml", wp::model(6));
  const fs::path csv = dir.path() / "winch.csv";
  const hardening::RunResult r =
      hardening::run_lagrange(dir.path(), {"simulate", (dir.path() / "winch.yaml").string(), "-q",
                                           "--rtol", "1e-11", "-o", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(hardening::slurp(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream cells(line); std::getline(cells, line, ',');) header.push_back(line);
  auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name;
    return static_cast<size_t>(at - header.begin());
  };
  const size_t ell = column("drum.reeled_out"), load = column("drum.load");
  EXPECT_LT(column("line.tension_ground"), header.size());
  size_t rows = 0;
  while (std::getline(in, line)) {
    std::vector<double> cells;
    for (std::istringstream row(line); std::getline(row, line, ',');)
      cells.push_back(std::stod(line));
    ASSERT_EQ(cells.size(), header.size());
    const double expected = hanging_pull(cells[ell], wp::acceleration(cells[ell]));
    ASSERT_NEAR(cells[load], expected, 1e-7 * expected) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 401u);  // t = 0 … 4 every 0.01 s
}

// A line of length 2 from a fixed anchor to a payload, swinging from `angle` (0: hanging at rest).
std::string anchored_line(const std::string& kind, double angle) {
  return fmt::format(R"(name: anchored line
parameters: {{mu: 0.3, mp: 1.5, g: 9.81, ell: 2}}
gravity: [0, 0, -g]
coordinates:
  px: {{initial: {}}}
  py: {{initial: 0}}
  pz: {{initial: {}}}
points: {{load: [px, py, pz]}}
particles: {{load: mp}}
tethers:
  line: {{between: [[0, 0, 0], load], length: ell, segments: 3, model: {}, mass_per_length: mu}}
)",
                     2 * std::sin(angle), -2 * std::cos(angle), kind);
}

TEST(Loads, AnchorOfAHangingLineCarriesTheWholeWeight) {
  const double weight = (0.3 * 2 + 1.5) * 9.81;
  for (const std::string kind : {"lumped", "full"}) {
    Loaded sys = load_string(anchored_line(kind, 0));
    const Trajectory tr = sys.run(tight(sys, 1, 0.1));
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    // What the first segment misses: one node (lumped, μℓ/4) or half a segment (full, μℓ/6).
    const double missing = (kind == "lumped" ? 0.3 * 2 / 4 : 0.3 * 2 / 6) * 9.81;
    for (size_t r = 0; r < tr.rows(); ++r) {
      EXPECT_NEAR(tr.at(r, "line.load_ground"), weight, 1e-9 * weight) << kind;
      EXPECT_NEAR(tr.at(r, "line.tension_ground"), weight - missing, 1e-9 * weight) << kind;
    }
  }
}

// The anchor's load is the weight of everything minus the rate of change of its momentum,
// P = Σ m ṙ (lumped) or Σ mₛ (ṙₐ + ṙ_b)/2 + m_p ṙ_load (full), with accelerations from the
// solved dynamics at each sample.
TEST(Loads, AnchorOfASwingingLineBalancesTheLinesMomentum) {
  for (const std::string kind : {"lumped", "full"}) {
    Loaded sys = load_string(anchored_line(kind, 0.6));
    const Trajectory tr = sys.run(tight(sys, 1.5, 0.05));
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    const CompiledModel& cm = *sys.compiled;
    auto index = [&](const std::string& name) {
      return static_cast<size_t>(
          std::find(cm.coordinate_names.begin(), cm.coordinate_names.end(), name) -
          cm.coordinate_names.begin());
    };
    const double mu = 0.3, ell = 2, mp = 1.5, g = 9.81;
    const size_t n = 3, width = tr.columns.size();
    std::vector<double> qdot(cm.nq), a(cm.nv), lambda(cm.m);
    for (size_t r = 0; r < tr.rows(); ++r) {
      const double* row = &tr.data[r * width];
      sys.dynamics->forward(row[0], row + 1, row + 1 + cm.nq, qdot.data(), a.data(), lambda.data());
      // r̈ of node j (node 0 is the anchor, node n the payload).
      auto node_acc = [&](size_t j, size_t k) {
        if (j == 0) return 0.0;
        const std::string axis(1, "xyz"[k]);
        return a[index(j == n ? "p" + axis : fmt::format("line.node{}.{}", j, axis))];
      };
      std::array<double, 3> force{};
      for (size_t k = 0; k < 3; ++k) {
        double rate = mp * node_acc(n, k);
        for (size_t j = 0; j <= n; ++j)
          if (kind == "lumped")
            rate += mu * ell / (n + 1) * node_acc(j, k);
          else if (j > 0)
            rate += mu * ell / n * (node_acc(j - 1, k) + node_acc(j, k)) / 2;
        force[k] = (mu * ell + mp) * (k == 2 ? -g : 0.0) - rate;
      }
      const double expected = std::hypot(force[0], force[1], force[2]);
      ASSERT_NEAR(tr.at(r, "line.load_ground"), expected, 1e-8 * expected)
          << kind << ", t = " << row[0];
    }
  }
}

}  // namespace
}  // namespace lagrange::testing
