// Hostile and odd inputs through the command line (issue 25 items 6, 8 and 9): `visual:` checked
// with the rest of the model, located messages in words where an internal one leaked, files that
// never end, and Ctrl-C in every long phase.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

const std::string kPendulumText =
    "parameters: {m: 1.0, l: 1.0, g: 9.81}\ncoordinates:\n  theta: {initial: 1.0}\n"
    "points:\n  bob: [l*sin(theta), -l*cos(theta), 0]\nparticles: {bob: m}\n"
    "gravity: [0, -g, 0]\nsimulate: {t_end: 1, output_step: 0.01}\n";

std::vector<BadModel> bad_visuals() {
  return {
      {"visual as a number", kPendulumText + "visual: 5\n", "expected a map for visual"},
      {"unknown visual key", kPendulumText + "visual: {colour: {bob: red}}\n", "'colour'"},
      {"colour as a list", kPendulumText + "visual: {color: {bob: [1, 2]}}\n", "colour of 'bob'"},
      {"colour of nothing", kPendulumText + "visual: {color: {nobody: red}}\n", "'nobody'"},
      {"short hex colour", kPendulumText + "visual: {color: {bob: '#12345'}}\n", "'#12345'"},
      {"hex colour with a non-digit", kPendulumText + "visual: {color: {bob: '#12345g'}}\n",
       "'#12345g'"},
      {"unknown colour name", kPendulumText + "visual: {color: {bob: redd}}\n", "'redd'"},
      // once a SIGSEGV (exit 139) in the report's regular expression
      {"50000-letter colour name",
       kPendulumText + "visual: {color: {bob: " + std::string(50000, 'a') + "}}\n", "colour"},
      {"negative size", kPendulumText + "visual: {size: {bob: -1}}\n", "positive number"},
      {"NaN size", kPendulumText + "visual: {size: {bob: .nan}}\n", "positive number"},
      {"size as text", kPendulumText + "visual: {size: {bob: big}}\n", "positive number"},
      {"hide as a name", kPendulumText + "visual: {hide: bob}\n", "visual.hide"},
      {"trail of nothing", kPendulumText + "visual: {trail: [nobody]}\n", "'nobody'"},
  };
}

class BadVisual : public ::testing::TestWithParam<BadModel> {};

TEST_P(BadVisual, Exit1Located) {
  expect_model_error(GetParam(), "visual");
}

INSTANTIATE_TEST_SUITE_P(Cli, BadVisual, ::testing::ValuesIn(bad_visuals()), label_name);

TEST(Visual, CheckFindsTheMistakeAndAcceptsAGoodSection) {
  ScratchDir dir("visual-check");
  const fs::path bad = dir.path() / "bad.yaml", good = dir.path() / "good.yaml";
  spit(bad, kPendulumText + "visual:\n  size: {bob: -0.1}\n");
  const RunResult r = run_lagrange(dir.path(), {"check", bad.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find("bad.yaml:10:15: error: expected a positive number (metres) as the size "
                       "of 'bob', got '-0.1'"),
            std::string::npos)
      << r.err;
  spit(good, kPendulumText +
                 "visual: {color: {bob: DarkRed}, size: {bob: 0.1}, trail: [bob], hide: []}\n");
  const RunResult ok = run_lagrange(dir.path(), {"check", good.string()});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// A two-joint URDF arm; `upper` carries its mass on the axis of `elbow` when `on_axis`.
std::string arm(bool on_axis) {
  const std::string lower_inertial =
      on_axis ? "<inertial><mass value=\"1\"/>"
                "<inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial>"
              : "<inertial><origin xyz=\"0.5 0 0\"/><mass value=\"1\"/>"
                "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>"
                "</inertial>";
  return "<robot name=\"arm\">\n<link name=\"base\"/>\n"
         "<link name=\"upper\"><inertial><origin xyz=\"0.5 0 0\"/><mass value=\"1\"/>"
         "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>"
         "</inertial></link>\n"
         "<link name=\"lower\">" +
         lower_inertial +
         "</link>\n"
         "<joint name=\"shoulder\" type=\"revolute\"><parent link=\"base\"/>"
         "<child link=\"upper\"/><axis xyz=\"0 0 1\"/></joint>\n"
         "<joint name=\"elbow\" type=\"revolute\"><parent link=\"upper\"/>"
         "<child link=\"lower\"/><origin xyz=\"1 0 0\"/><axis xyz=\"0 0 1\"/></joint>\n"
         "</robot>\n";
}

TEST(Urdf, TheMapFormTakesInitialWithoutRate) {
  // "invalid node; this may result from using a map iterator as a sequence iterator" before
  ScratchDir dir("urdf-map");
  spit(dir.path() / "arm.urdf", arm(false));
  const fs::path model = dir.path() / "m.yaml", csv = dir.path() / "out.csv";
  spit(model,
       "urdf: {file: arm.urdf, initial: {elbow: 0.5}}\ngravity: [0, -9.81, 0]\n"
       "simulate: {t_end: 0.1, output_step: 0.1}\n");
  const RunResult r =
      run_lagrange(dir.path(), {"simulate", model.string(), "-o", csv.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = slurp(csv);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,shoulder,elbow,shoulder_dot,elbow_dot,kinetic,potential,energy");
  // the first row starts at elbow = 0.5, at rest
  EXPECT_EQ(text.substr(text.find('\n') + 1, 9), "0,0,0.5,0");
  spit(model, "urdf: {file: arm.urdf, rate: {shoulder: 0.25}}\n");
  EXPECT_EQ(run_lagrange(dir.path(), {"check", model.string()}).exit_code, 0);
}

TEST(Urdf, AFileThatCannotBeReadIsTheModelsMistakeAtItsLine) {
  ScratchDir dir("urdf-missing");
  const fs::path model = dir.path() / "m.yaml";
  spit(model, "urdf: \"\"\n");
  RunResult r = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("m.yaml:1:7: error: expected the name of a URDF file in urdf, got ''"),
            std::string::npos)
      << r.err;
  spit(model, "gravity: [0, 0, -9.81]\nurdf: {file: robots/none.urdf}\n");
  r = run_lagrange(dir.path(), {"check", model.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("m.yaml:2:14: error: cannot open the URDF file"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("no such file"), std::string::npos) << r.err;
}

// URDF files get the model files' 16 MiB cap (issue 37 item 13): a 30 MB URDF took 39 s and
// 485 MB before its coordinates were counted, and a 300 MB one was read whole. Named in a model
// file, it is refused at its line before it is read; given on its own, once 16 MiB are read.
TEST(Urdf, AFileOverSixteenMebibytesIsRefused) {
  ScratchDir dir("urdf-too-large");
  const fs::path urdf = dir.path() / "huge.urdf";
  spit(urdf, "<robot name=\"huge\">\n");
  fs::resize_file(urdf, (size_t{16} << 20) + 1);  // sparse: costs no disk
  const fs::path model = dir.path() / "m.yaml";
  spit(model, "gravity: [0, 0, -9.81]\nurdf: {file: huge.urdf}\n");
  RunResult r = run_lagrange(dir.path(), {"check", model.string()}, std::chrono::seconds(30));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("m.yaml:2:14: error: expected a URDF file of at most 16 MiB, got '"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("huge.urdf' of 16.0 MiB"), std::string::npos) << r.err;
  Child alone(dir.path(), {"check", urdf.string()});
  alone.limit_memory(rlim_t{1} << 30);
  r = alone.wait(std::chrono::seconds(30));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("huge.urdf: error: expected a URDF file of at most 16 MiB, got more"),
            std::string::npos)
      << r.err;
  EXPECT_LT(r.max_rss_kb, 200 * 1024) << "peak memory";
}

TEST(Urdf, AFileNameWithAQuoteIsAName) {
  ScratchDir dir("urdf-quote");
  const fs::path urdf = dir.path() / "it's an arm.urdf";
  spit(urdf, arm(false));
  const RunResult r = run_lagrange(dir.path(), {"check", urdf.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("arm: 2 coordinates"), std::string::npos) << r.out;
}

TEST(Urdf, AMassOnItsJointAxisIsFoundBySimulateAsByCheck) {
  // simulate once said "power::eval(): division by zero" where check named the coordinate
  ScratchDir dir("urdf-axis");
  const fs::path urdf = dir.path() / "arm.urdf";
  spit(urdf, arm(true));
  for (const char* command : {"check", "simulate"}) {
    SCOPED_TRACE(command);
    const RunResult r = run_lagrange(dir.path(), {command, urdf.string()});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("coordinate 'elbow' has no inertia at the initial state"),
              std::string::npos)
        << r.err;
  }
}

TEST(ModelFile, AFileThatNeverEndsIsRefusedWithBoundedMemory) {
  // /dev/zero was read until std::bad_alloc
  ScratchDir dir("dev-zero");
  const RunResult r = run_lagrange(dir.path(), {"check", "/dev/zero"}, std::chrono::seconds(60));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/dev/zero: error: expected a model file of at most 16 MiB, got more"),
            std::string::npos)
      << r.err;
  EXPECT_LT(r.max_rss_kb, 400 * 1024);
}

TEST(SizeLimits, TwoThousandCoordinatesCountWrittenAndGeneratedTogether) {
  // 2000 written coordinates and a link's joint: 2001 once passed where the docs say 2000
  std::string yaml = "coordinates: {";
  for (int i = 0; i < 2000; ++i) yaml += (i ? ", q" : "q") + std::to_string(i) + ": {initial: 0}";
  yaml +=
      "}\npotential: q0^2\nlinks:\n  arm:\n    joint: {name: elbow, type: revolute}\n"
      "    mass: 1\n    com: [1, 0, 0]\n    inertia: [0, 0, 0.1]\n";
  ScratchDir dir("limit-2001");
  spit(dir.path() / "m.yaml", yaml);
  const RunResult r = run_lagrange(dir.path(), {"check", (dir.path() / "m.yaml").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("m.yaml:5:19: error: expected at most 2000 coordinates in the model "
                       "(written and generated together), got more"),
            std::string::npos)
      << r.err.substr(0, 500);
}

TEST(SizeLimits, ATenThousandLinkUrdfIsRefusedBeforeItsFramesAreBuilt) {
  // once 12 minutes and 4.9 GB before anything was said
  std::string urdf = "<robot name=\"snake\">\n<link name=\"l0\"/>\n";
  for (int i = 1; i <= 10000; ++i) {
    const std::string n = std::to_string(i), p = std::to_string(i - 1);
    urdf += "<link name=\"l" + n +
            "\"><inertial><origin xyz=\"0.05 0 0\"/><mass value=\"0.1\"/><inertia ixx=\"1e-4\" "
            "ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial></link>\n"
            "<joint name=\"j" +
            n + "\" type=\"revolute\"><parent link=\"l" + p + "\"/><child link=\"l" + n +
            "\"/><origin xyz=\"0.1 0 0\"/><axis xyz=\"0 0 1\"/></joint>\n";
  }
  urdf += "</robot>\n";
  ScratchDir dir("limit-urdf");
  spit(dir.path() / "snake.urdf", urdf);
  const RunResult r = run_lagrange(dir.path(), {"check", (dir.path() / "snake.urdf").string()},
                                   std::chrono::seconds(120));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("expected at most 2000 coordinates in the model"), std::string::npos)
      << r.err.substr(0, 500);
  EXPECT_NE(r.err.find("has 10000 movable joints"), std::string::npos) << r.err.substr(0, 500);
  EXPECT_LT(r.max_rss_kb, 1024 * 1024);
}

// Ctrl-C `delay` after the start; the run must end with 130 within `limit` of the signal.
RunResult interrupt_after(const fs::path& dir, const std::vector<std::string>& args,
                          std::chrono::milliseconds delay, double limit) {
  Child child(dir, args);
  std::this_thread::sleep_for(delay);
  const auto sent = std::chrono::steady_clock::now();
  child.signal(SIGINT);
  RunResult r = child.wait(std::chrono::seconds(120));
  const double after =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_LT(after, limit) << "seconds from SIGINT to exit";
  return r;
}

TEST(Interruption, AReadBlockedOnAFifoEndsAt130) {
  ScratchDir dir("sigint-fifo");
  const fs::path fifo = dir.path() / "model.yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const RunResult r =
      interrupt_after(dir.path(), {"check", fifo.string()}, std::chrono::milliseconds(500), 5.0);
  EXPECT_NE(r.err.find("lagrange: interrupted"), std::string::npos) << r.err;
}

/// A 40-link planar chain with a parameter k (its first link's mass): derived in the Lagrangian
/// form, asked for, it takes seconds.
std::string slow_chain() {
  std::string yaml = "parameters: {k: 1}\ngravity: [0, -9.81, 0]\nlinks:\n";
  for (int i = 0; i < 40; ++i) {
    yaml += "  l" + std::to_string(i) + ":\n";
    if (i > 0) yaml += "    parent: l" + std::to_string(i - 1) + "\n";
    yaml += "    joint: {name: q" + std::to_string(i) +
            ", type: revolute, origin: {xyz: [1, 0, 0]}, initial: 0.1}\n" +
            (i == 0 ? "    mass: k\n" : "    mass: 1\n") +
            "    com: [0.5, 0, 0]\n    inertia: [0, 0, 0.1]\n";
  }
  return yaml;
}

TEST(Interruption, ASlowCheckEndsAt130) {
  ScratchDir dir("sigint-check");
  spit(dir.path() / "chain.yaml", slow_chain());
  (void)interrupt_after(dir.path(),
                        {"check", (dir.path() / "chain.yaml").string(), "--dynamics", "lagrangian"},
                        std::chrono::milliseconds(1500), 5.0);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"chain.yaml"});
}

// The same while a sweep derives (issue 37 item 10): once ignored for 20 s and more; now it ends
// at once, as `check` and `simulate` do, with nothing written.
TEST(Interruption, ASweepThatIsStillDerivingEndsAt130) {
  ScratchDir dir("sigint-sweep");
  spit(dir.path() / "chain.yaml", slow_chain());
  (void)interrupt_after(
      dir.path(),
      {"sweep", (dir.path() / "chain.yaml").string(), "--vary", "k=1,2", "--dynamics", "lagrangian",
       "--compile", "off", "-q", "-o", (dir.path() / "study").string()},
      std::chrono::milliseconds(1500), 5.0);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"chain.yaml"});
}

TEST(Interruption, ARunBetweenFarSamplesKeepsItsRows) {
  // One sample a simulated day: Ctrl-C must not wait for the next one. The signal comes 0.6 s in:
  // after the 0.05 s derivation, and before ida spends its million steps per interval (1.3 s on
  // an idle machine, where it then fails with IDA_TOO_MUCH_WORK).
  ScratchDir dir("sigint-between");
  const fs::path csv = dir.path() / "out.csv";
  for (const char* method : {"dop853", "ida"}) {
    SCOPED_TRACE(method);
    const RunResult r = interrupt_after(
        dir.path(),
        {"simulate", std::string(LAGRANGE_SOURCE_DIR) + "/examples/double_pendulum.yaml", "-o",
         csv.string(), "-q", "--t-end", "1e7", "--output-step", "86400", "--integrator", method},
        std::chrono::milliseconds(600), 5.0);
    EXPECT_NE(r.err.find("interrupted at t = 0"), std::string::npos) << r.err;
    const auto side = nlohmann::json::parse(slurp(dir.path() / "out.csv.json"));
    EXPECT_EQ(side.at("status"), "interrupted");
    EXPECT_EQ(side.at("rows"), 1);  // the start
  }
}

/// `text` with every `{key}` replaced by its value.
std::string expand(std::string text, const std::map<std::string, std::string>& values) {
  for (const auto& [key, value] : values)
    for (size_t at; (at = text.find("{" + key + "}")) != std::string::npos;)
      text.replace(at, key.size() + 2, value);
  return text;
}

/// `text` without the spaces at its ends.
std::string trimmed(const std::string& text) {
  const size_t first = text.find_first_not_of(' '), last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

// The hostile command lines of issue 37 (tests/hardening/data/hostile_commands.txt): each exits
// with its code and message, quickly, and writes nothing.
TEST(HostileCommands, EachGivesItsExitCodeAndMessageAndWritesNothing) {
  ScratchDir dir("hostile-commands");
  const std::string source = LAGRANGE_SOURCE_DIR;
  const std::map<std::string, std::string> values{
      {"pendulum", source + "/examples/pendulum.yaml"},
      {"double_pendulum", source + "/examples/double_pendulum.yaml"},
      {"elastic_pendulum", source + "/examples/elastic_pendulum.yaml"},
      {"cartesian_pendulum", source + "/examples/cartesian_pendulum.yaml"},
      {"dir", dir.path().string()}};
  std::istringstream table(slurp(source + "/tests/hardening/data/hostile_commands.txt"));
  size_t cases = 0;
  for (std::string line; std::getline(table, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t bar1 = line.find(" | "), bar2 = line.find(" | ", bar1 + 3);
    ASSERT_NE(bar2, std::string::npos) << "malformed line: " << line;
    const int exit_code = std::stoi(line.substr(0, bar1));
    const std::string fragment = trimmed(line.substr(bar1 + 3, bar2 - bar1 - 3));
    std::vector<std::string> args;
    std::istringstream words(expand(line.substr(bar2 + 3), values));
    for (std::string word; words >> word;) args.push_back(word == "''" ? "" : word);
    SCOPED_TRACE(line);
    const RunResult r = run_lagrange(dir.path(), args, std::chrono::seconds(60));
    EXPECT_EQ(r.exit_code, exit_code) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
    EXPECT_EQ(dir.files(), std::vector<std::string>{});
    ++cases;
  }
  EXPECT_GE(cases, 20u);
}

// A model file's metric named like a column of the summary (a parameter, `status`, `case`) would
// overwrite that column (issue 37 item 7): `simulate` and `check` (item 17) refuse it, located.
TEST(HostileCommands, AMetricCannotShadowASummaryColumn) {
  for (const std::string name : {"m", "status", "case"}) {
    const std::string yaml = kPendulumText + "metrics:\n  " + name + ": final(theta)\n";
    expect_model_error({"metric named like a column", yaml, "is named like"}, "metric-" + name);
    ScratchDir dir("metric-check-" + name);
    spit(dir.path() / "bad.yaml", yaml);
    const RunResult r = run_lagrange(dir.path(), {"check", (dir.path() / "bad.yaml").string()});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(std::regex_search(
        r.err, std::regex("bad\\.yaml:10:[0-9]+: error: metric '" + name + "' is named like")))
        << r.err;
  }
}

// A saved trajectory with a value that is not a finite number (`report` reads what simulate, which
// writes finite values, never wrote): refused at its line (exit 2) instead of laying out a scene
// of infinite extent (issue 37, the double-to-integer audit: log10 of it was cast to int).
TEST(HostileCommands, AReportOfANonFiniteTrajectoryIsRefused) {
  ScratchDir dir("report-inf");
  spit(dir.path() / "model.yaml", kPendulumText);
  for (const std::string value : {"inf", "-1e999", "nan"}) {
    spit(dir.path() / "traj.csv", "t,theta,theta_dot\n0,1,0\n0.01," + value + ",0\n");
    const RunResult r = run_lagrange(
        dir.path(), {"report", (dir.path() / "model.yaml").string(),
                     (dir.path() / "traj.csv").string(), "-o", (dir.path() / "r.html").string()});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("traj.csv:3: expected a finite number, got '" + value + "'"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "r.html"));
  }
}

// A stop condition that is NaN at every sample never fires (issue 37 item 20): the run ends as
// before (exit 0, every row) and says so once.
TEST(HostileCommands, AStopConditionThatIsNeverANumberIsWarnedOnce) {
  ScratchDir dir("stop-nan");
  spit(dir.path() / "model.yaml", kPendulumText + "stop_when:\n  never: sqrt(theta - 100) > 1\n");
  const RunResult r = run_lagrange(
      dir.path(), {"simulate", (dir.path() / "model.yaml").string(), "--compile", "off", "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string warning =
      "warning: stop condition never: sqrt(theta - 100) > 1 was not a "
      "number at every sample (";
  ASSERT_NE(r.err.find(warning), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, r.err.find(warning) + 1), std::string::npos) << r.err;
}

// linearize --at-trim far out (θ = 2π·10⁸, where trim's tolerance is its rounding floor, 5·10⁻⁶)
// says "equilibrium found" and then does not contradict it with "not an equilibrium" (issue 37
// item 4).
TEST(HostileCommands, LinearizeAtTrimNeverContradictsTheTrim) {
  ScratchDir dir("at-trim-far");
  const RunResult r = run_lagrange(
      dir.path(), {"linearize", std::string(LAGRANGE_SOURCE_DIR) + "/examples/pendulum.yaml",
                   "--at-trim", "--at", "theta=628318530.7"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("equilibrium found"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("not an equilibrium"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lagrange::hardening
