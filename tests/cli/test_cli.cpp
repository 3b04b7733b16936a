// The `lagrange` command end to end: exit codes, messages, files written or not.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli/shell_run.hpp"
#include "support/scratch_dir.hpp"
#include "support/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

using Result = lagrange::testing::ShellResult;

Result run(const std::string& args) {
  return lagrange::testing::run_shell(args);
}

using lagrange::test::example_path;

fs::path scratch(const std::string& name) {
  static const lagrange::test::ScratchDir folder("cli");
  const fs::path& dir = folder.path();
  fs::remove(dir / name);
  fs::remove(dir / (name + ".json"));
  return dir / name;
}

fs::path write_model(const std::string& name, const std::string& text) {
  const fs::path p = scratch(name);
  std::ofstream(p) << text;
  return p;
}

TEST(Cli, SimulateWritesCsvSidecarAndPlot) {
  const fs::path csv = scratch("dp.csv"), svg = scratch("dp.svg");
  const Result r = run("simulate " + example_path("double_pendulum.yaml") + " --t-end 1 -o " +
                       csv.string() + " --plot " + svg.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "t,theta1,theta2,theta1_dot,theta2_dot,kinetic,potential,energy,x2,y2");
  EXPECT_TRUE(fs::exists(csv.string() + ".json"));
  std::ifstream plot(svg);
  std::string first;
  std::getline(plot, first);
  EXPECT_NE(first.find("<?xml"), std::string::npos);
}

// issue 8, item 8: --plot by extension (PNG through gnuplot's pngcairo), -o and --plot into
// directories that do not exist yet, and plot options checked before anything is written.
TEST(Cli, PlotsPngAndCreatesMissingDirectories) {
  const fs::path dir = scratch("new_dir");
  fs::remove_all(dir);
  const fs::path csv = dir / "runs" / "p.csv", png = dir / "plots" / "p.png";
  const Result r = run("simulate " + example_path("pendulum.yaml") + " --t-end 1 -q -o " +
                       csv.string() + " --plot " + png.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(csv));
  EXPECT_TRUE(fs::exists(csv.string() + ".json"));
  std::ifstream in(png, std::ios::binary);
  std::string magic(8, '\0');
  in.read(magic.data(), 8);
  EXPECT_EQ(magic, std::string("\x89PNG\r\n\x1a\n", 8));
  fs::remove_all(dir);
}

TEST(Cli, PlotOptionsAreCheckedBeforeTheRun) {
  const fs::path csv = scratch("refused.csv");
  const Result pdf = run("simulate " + example_path("pendulum.yaml") + " -o " + csv.string() +
                         " --plot " + scratch("p.pdf").string());
  EXPECT_EQ(pdf.code, 2);
  EXPECT_NE(pdf.output.find("--plot: expected a plot file ending in .svg or .png, got '"),
            std::string::npos)
      << pdf.output;
  const Result column = run("simulate " + example_path("pendulum.yaml") + " -o " + csv.string() +
                            " --plot " + scratch("p.svg").string() + " --plot-columns nope");
  EXPECT_EQ(column.code, 2);
  EXPECT_NE(column.output.find("--plot-columns: no column 'nope'"), std::string::npos)
      << column.output;
  EXPECT_FALSE(fs::exists(csv));
  EXPECT_FALSE(fs::exists(csv.string() + ".json"));
}

// The summary's energy change is relative to the starting energy, and absolute when that is
// zero next to the kinetic and potential energies: the Cartesian pendulum released at rest from
// the horizontal starts at E = 0, where the quotient printed "relative change 2.03e+290".
TEST(Cli, EnergyChangeIsAbsoluteWhenTheStartingEnergyIsZero) {
  auto change = [](const std::string& output, const std::string& kind) {
    const std::string key = "(" + kind + " change ";
    const size_t at = output.find(key);
    if (at == std::string::npos) return -1.0;
    return std::stod(output.substr(at + key.size()));
  };
  const Result zero = run("simulate " + std::string(LAGRANGE_SOURCE_DIR) +
                          "/docs/tutorials/cartesian_pendulum.yaml --t-end 1");
  ASSERT_EQ(zero.code, 0) << zero.output;
  EXPECT_NE(zero.output.find("energy 0 -> "), std::string::npos) << zero.output;
  EXPECT_EQ(zero.output.find("relative change"), std::string::npos) << zero.output;
  const double absolute = change(zero.output, "absolute");
  EXPECT_GE(absolute, 0.0) << zero.output;
  EXPECT_LT(absolute, 1e-6) << zero.output;  // joules; rtol 1e-10 over one second
  const Result nonzero = run("simulate " + example_path("pendulum.yaml") + " --t-end 1");
  ASSERT_EQ(nonzero.code, 0) << nonzero.output;
  EXPECT_EQ(nonzero.output.find("absolute change"), std::string::npos) << nonzero.output;
  const double relative = change(nonzero.output, "relative");
  EXPECT_GE(relative, 0.0) << nonzero.output;
  EXPECT_LT(relative, 1e-6) << nonzero.output;
}

TEST(Cli, SetChangesParameterWithoutEditingTheFile) {
  const fs::path a = scratch("a.csv"), b = scratch("b.csv");
  ASSERT_EQ(
      run("simulate " + example_path("pendulum.yaml") + " -q --t-end 1 -o " + a.string()).code, 0);
  ASSERT_EQ(
      run("simulate " + example_path("pendulum.yaml") + " -q --t-end 2 --set l=4 -o " + b.string())
          .code,
      0);
  auto last_theta = [](const fs::path& p) {
    std::ifstream in(p);
    std::string line, last;
    while (std::getline(in, line)) last = line;
    return std::stod(last.substr(last.find(',') + 1));
  };
  EXPECT_NEAR(last_theta(a), last_theta(b), 1e-6);  // l → 4l doubles the time scale
  const Result bad = run("simulate " + example_path("pendulum.yaml") + " --set nope=1");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("unknown parameter 'nope'"), std::string::npos) << bad.output;
}

TEST(Cli, DeriveShowsSeedEquation) {
  const Result r = run("derive " + example_path("pendulum.yaml"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("Mass matrix"), std::string::npos);
  const Result tex = run("derive " + example_path("cartesian_pendulum.yaml") + " --format latex");
  ASSERT_EQ(tex.code, 0) << tex.output;
  EXPECT_NE(tex.output.find("\\begin{align*}"), std::string::npos);
  const Result json = run("derive " + example_path("elastic_pendulum.yaml") + " --format json");
  ASSERT_EQ(json.code, 0) << json.output;
  EXPECT_NE(json.output.find("\"M\""), std::string::npos);
}

// docs/theory.md §4.4: a free body's equations in the seed's form, a posed body's ω and T.
TEST(Cli, DeriveShowsBodyEquations) {
  const Result top = run("derive " + example_path("heavy_top.yaml"));
  ASSERT_EQ(top.code, 0) << top.output;
  for (const char* s :
       {"Rigid body 'top': free in SO(3)", "m r'' + dV/dr = F_r",
        "J w' + w x (J w) + 2P(dV/dR) = F_rot", "R' = R (Omega + Xi)", "top.R11' = "})
    EXPECT_NE(top.output.find(s), std::string::npos) << s << "\n" << top.output;
  // m r_z'' + m g = −λ_z (GiNaC's term order varies between processes: check the pieces).
  const size_t eq = top.output.find(" = -lambda_pivot.z\n");
  ASSERT_NE(eq, std::string::npos) << top.output;
  const std::string line =
      top.output.substr(top.output.rfind('\n', eq) + 1, eq - top.output.rfind('\n', eq));
  EXPECT_NE(line.find("top.az"), std::string::npos) << line;
  EXPECT_TRUE(line.find("m*g") != std::string::npos || line.find("g*m") != std::string::npos)
      << line;
  const Result bar = run("derive " + example_path("compound_pendulum_planar.yaml"));
  ASSERT_EQ(bar.code, 0) << bar.output;
  EXPECT_NE(bar.output.find("w_bar = unskew(R^T R') = [0, 0, theta_dot]"), std::string::npos)
      << bar.output;
  const Result tex = run("derive " + example_path("tumbling_brick.yaml") + " --format latex");
  ASSERT_EQ(tex.code, 0) << tex.output;
  EXPECT_NE(tex.output.find("J_{\\mathrm{brick}}"), std::string::npos) << tex.output;
}

struct BadCase {
  const char* name;
  std::string yaml;
  const char* location;  // expected "file:line:column" suffix after the file name
  const char* fragment;  // expected in the message
};

// A bar posed by one angle q = 0.5 with the given `rotation:` (line 9, column 15).
std::string posed_bar(const std::string& rotation) {
  return "parameters: {m: 1, l: 1, g: 9.81}\ncoordinates:\n  q: {initial: 0.5}\nbodies:\n  bar:\n"
         "    mass: m\n    inertia: [1, 1, 1]\n    position: rot_z(q)*[0, -l/2, 0]\n"
         "    rotation: \"" +
         rotation + "\"\ngravity: [0, -g, 0]\n";
}

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, Exit1Located) {
  const BadCase& c = GetParam();
  const fs::path model = write_model(std::string(c.name) + ".yaml", c.yaml);
  const fs::path csv = scratch(std::string(c.name) + ".csv");
  const Result r = run("simulate " + model.string() + " -o " + csv.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(model.string() + ":" + c.location), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(c.fragment), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(csv));
  EXPECT_FALSE(fs::exists(csv.string() + ".json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cli, BadInput,
    ::testing::Values(
        BadCase{"yaml_syntax", "name: x\ncoordinates:\n  q: {initial: 1\n", "4:", "YAML"},
        BadCase{"unknown_name", "coordinates:\n  q: {initial: 1}\npotential: k*q^2\n", "3:12",
                "'k'"},
        BadCase{"wrong_vector_size", "coordinates:\n  q: {initial: 1}\npoints:\n  p: [q, 0]\n",
                "4:", "3"},
        BadCase{"missing_initial", "coordinates:\n  q: {rate: 1}\n", "2:", "initial"},
        // issue 8, item 1: a posed body's rotation must be a rotation at every state
        BadCase{"rotation_scaled", posed_bar("rot_z(q)*2"),
                "9:15: ", "got ‖RᵀR − 1‖ = 5.2 at the initial state (q = 0.5)"},
        BadCase{"rotation_sign_slip",
                posed_bar("[[cos(q), sin(q), 0], [sin(q), cos(q), 0], [0, 0, 1]]"),
                "9:15: ", "for the rotation of body 'bar', got ‖RᵀR − 1‖ ="},
        BadCase{"rotation_reflection",
                posed_bar("[[cos(q), -sin(q), 0], [sin(q), cos(q), 0], [0, 0, -1]]"),
                "9:15: ", "got det R = -1 at the initial state (q = 0.5)"},
        BadCase{"rotation_only_at_start",
                posed_bar("[[cos(q), -2*q*sin(q), 0], [2*q*sin(q), cos(q), 0], [0, 0, 1]]"),
                "9:15: ", "at a state drawn by the check (q = "},
        // issue 8, item 12: exact arithmetic is bounded where the reader folds numbers
        BadCase{"huge_exact_power",
                "coordinates:\n  q: {initial: 1}\nkinetic: der(q)^2/2\npotential: "
                "(((2*q)^999)^999)^999\n",
                "4:24: ", "expected exact numbers of at most 10000 digits"},
        // issue 8, item 8: spellings from other languages
        BadCase{"double_star_power",
                "parameters: {k: 1}\ncoordinates:\n  q: {initial: 1}\nkinetic: "
                "der(q)^2/2\npotential: k*q**2/2\n",
                "5:15: ", "got '**' (did you mean '^'? powers are written a^b)"},
        BadCase{"ln_for_log",
                "coordinates:\n  q: {initial: 1}\nkinetic: der(q)^2/2\npotential: ln(q)\n",
                "4:12: ", "unknown function 'ln' (did you mean 'log'?)"},
        BadCase{"tab_indent", "coordinates:\n\tq: {initial: 1}\n",
                "2:1: ", "YAML forbids tabs for indentation"},
        BadCase{"tab_after_spaces",
                "parameters: {m: 1}\ncoordinates:\n  q: {initial: 1}\n  \tp: {initial: 2}\n",
                "4:3: ", "YAML forbids tabs for indentation"},
        BadCase{"tab_before_comment",
                "coordinates:\n  q: {initial: 1}\nkinetic: der(q)^2/2\n\t# note\n",
                "4:1: ", "YAML forbids tabs for indentation"}),
    [](const auto& info) { return std::string(info.param.name); });

// issue 8, item 12: a fuzz finding that once kept `check` busy for minutes.
TEST(Cli, PowerTowerOfLongLiteralsEndsQuickly) {
  const std::string tower =
      std::string(LAGRANGE_SOURCE_DIR) + "/tests/hardening/data/fuzz/model/abs-power-tower.yaml";
  const auto start = std::chrono::steady_clock::now();
  const Result r = run("check " + tower);
  EXPECT_EQ(r.code, 1) << r.output;  // 9^822223^… overflows: the force is not finite at x = 1
  EXPECT_NE(r.output.find("abs-power-tower.yaml:2:3: error: the dynamics cannot be evaluated at "
                          "the initial state"),
            std::string::npos)
      << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(Cli, MissingFileIsAModelError) {
  const Result r = run("simulate /nonexistent/model.yaml");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("/nonexistent/model.yaml"), std::string::npos) << r.output;
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run("simulate").code, 2);
  EXPECT_EQ(run("frobnicate x").code, 2);
}

TEST(Cli, CheckReportsInconsistentInitialState) {
  const fs::path model = write_model("inconsistent.yaml", R"(name: off
parameters: {m: 1, g: 9.81, l: 1}
coordinates:
  x: {initial: 0.9}
  y: {initial: -0.6}
points: {bob: [x, y, 0]}
particles: {bob: m}
gravity: [0, -g, 0]
constraints: {rod: (x^2 + y^2 - l^2)/2}
)");
  const Result r = run("check " + model.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("inconsistent"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("x: 0.9 ->"), std::string::npos) << r.output;
  EXPECT_EQ(run("check " + example_path("cartesian_pendulum.yaml")).code, 0);
}

}  // namespace

// `export --fmu` (docs/fmu.md): an FMU with the description and the binary in it, `--c` beside
// it; usage mistakes exit 2 with the reason and write nothing.
TEST(Cli, ExportFmu) {
  const fs::path fmu = scratch("pendulum.fmu"), c_dir = fmu.parent_path() / "pendulum_c";
  fs::remove_all(c_dir);
  const Result ok = run("export " + example_path("pendulum.yaml") + " --fmu " + fmu.string() +
                        " --fmi-type cs --c " + c_dir.string());
  ASSERT_EQ(ok.code, 0) << ok.output;
  EXPECT_NE(ok.output.find("FMI 2.0 Co-Simulation, 2 states"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::exists(c_dir / "lagrange_model.c"));
  const Result listing = lagrange::testing::run_shell_command("unzip -l " + fmu.string());
  EXPECT_NE(listing.output.find("modelDescription.xml"), std::string::npos) << listing.output;
  EXPECT_NE(listing.output.find("binaries/linux64/pendulum.so"), std::string::npos);
  const fs::path bad = scratch("pendulum.zip");
  const std::vector<std::pair<std::string, std::string>> mistakes{
      {"", "give --c DIR"},
      {" --fmu " + bad.string(), "ending in .fmu"},
      {" --c " + c_dir.string() + " --fmi-type me", "give --fmu FILE.fmu too"},
      {" --fmu " + fmu.string() + " --jacobian", "drop --jacobian"},
      {" --fmu " + fmu.string() + " --fmi-type cosim", "--fmi-type"}};
  for (const auto& [args, reason] : mistakes) {
    const Result r = run("export " + example_path("pendulum.yaml") + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(reason), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(bad));
}
