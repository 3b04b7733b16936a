// Figures the manual quotes for a shipped example are what the example gives as shipped (issue
// 20): the winch's agreement with the seed's closed form, read from the sentence of the tethers
// tutorial (docs/manual/tutorials/tethers.md; it was the README's until issue 39).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "support/test_paths.hpp"
#include "support/harness.hpp"

namespace lagrange::testing {
namespace {

std::string readme() {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/docs/manual/tutorials/tethers.md");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ReadmeFigures, WinchFollowsTheClosedFormAsQuoted) {
  std::smatch m;
  const std::string text = readme();
  ASSERT_TRUE(std::regex_search(
      text, m,
      std::regex(R"(cosh\(√\(μgR²/\(J \+ mR²\)\) t\) to ([0-9.e+-]+) relative at every output)")))
      << "the tethers tutorial's winch sentence changed; update this test with it";
  const double quoted = std::stod(m[1].str());
  Loaded sys = load_example("winch.yaml");
  SimulationOptions so = sys.options();
  sys.dynamics->set_baumgarte(baumgarte_rate(sys.model->stabilization, so.integrator.method));
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double R = 0.2, J = 0.05, mu = 0.4, L = 30, g = 9.81, theta0 = 5;
  const double omega = std::sqrt(mu * g * R * R / (J + mu * L * R * R));
  double worst = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    worst = std::max(
        worst, std::abs(tr.at(r, "drum.angle") / (theta0 * std::cosh(omega * tr.at(r, "t"))) - 1));
  // The quoted figure, rounded to one digit: within a factor of two either way.
  EXPECT_LT(worst, 2 * quoted) << "the tutorial quotes " << quoted;
  EXPECT_GT(worst, quoted / 2) << "the tutorial quotes " << quoted;
}

}  // namespace
}  // namespace lagrange::testing
