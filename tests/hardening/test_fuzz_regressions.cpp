// Fuzz findings kept as regression tests (issue 5): every input in tests/hardening/data/fuzz/
// that once crashed, hung or ran away in a fuzz target, replayed through the same code path as
// the target (fuzz/fuzz_model.cpp, fuzz/fuzz_expression.cpp). Each must end in a diagnosed error
// or a result, quickly. The fuzzers' seed corpora are replayed too.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "../fuzz/model_budget.hpp"
#include "../fuzz/sweep_input.hpp"
#include "../fuzz/urdf_input.hpp"
#include "hardening/cli_runner.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"
#include "model/expression_parser.hpp"

namespace lagrange::hardening {
namespace {

std::vector<fs::path> inputs_in(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

const fs::path kSource = LAGRANGE_SOURCE_DIR;

// fuzz_model's body: read, then derive + compile when small. Returns "ok" or the error message.
std::string replay_model(const std::string& text) {
  try {
    const Model model = read_model_string(text, "fuzz.yaml");
    if (fuzz::fits(model, fuzz::Budget{})) (void)compile(derive(model));
    return "ok";
  } catch (const ModelError& e) {
    return e.what();
  }
}

// fuzz_expression's body, with the same names in scope.
std::string replay_expression(const std::string& text) {
  GiNaC::symbol t("t"), x("x"), y("y"), m("m"), l("l");
  model::ParseContext ctx;
  ctx.resolve = [&](const std::string& name, size_t) -> std::optional<model::Value> {
    if (name == "t") return model::Value::of(GiNaC::ex(t));
    if (name == "x") return model::Value::of(GiNaC::ex(x));
    if (name == "y") return model::Value::of(GiNaC::ex(y));
    if (name == "m") return model::Value::of(GiNaC::ex(m));
    if (name == "l") return model::Value::of(GiNaC::ex(l));
    if (name == "p") return model::Value::of(Vec3{x, y, 0});
    if (name == "r") return model::Value::of(Vec3{l * GiNaC::sin(x), -l * GiNaC::cos(x), 0});
    return std::nullopt;
  };
  ctx.time_derivative = [&](const GiNaC::ex& e) { return e.diff(t) + e.diff(x) + e.diff(y); };
  (void)model::referenced_names(text);
  try {
    (void)model::parse_expression(text, ctx);
    return "ok";
  } catch (const model::ExprError& e) {
    return e.message;
  }
}

void replay_all(const std::vector<fs::path>& files,
                const std::function<std::string(const std::string&)>& replay) {
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    const auto start = std::chrono::steady_clock::now();
    std::string outcome;
    EXPECT_NO_THROW(outcome = replay(slurp(file)));
    EXPECT_FALSE(outcome.empty());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 10.0) << "slow input";
  }
}

TEST(FuzzRegressions, ModelFindingsAreDiagnosed) {
  replay_all(inputs_in(kSource / "tests/hardening/data/fuzz/model"), replay_model);
}

TEST(FuzzRegressions, ExpressionFindingsAreDiagnosed) {
  replay_all(inputs_in(kSource / "tests/hardening/data/fuzz/expression"), replay_expression);
}

TEST(FuzzRegressions, SeedCorporaReplay) {
  const auto examples = inputs_in(kSource / "examples");
  ASSERT_FALSE(examples.empty());
  for (const auto& file : examples) EXPECT_EQ(replay_model(slurp(file)), "ok") << file;
  replay_all(inputs_in(kSource / "fuzz/corpus/model"), replay_model);
  const auto expressions = inputs_in(kSource / "fuzz/corpus/expression");
  ASSERT_FALSE(expressions.empty());
  for (const auto& file : expressions) EXPECT_EQ(replay_expression(slurp(file)), "ok") << file;
}

// fuzz_sweep_spec's and fuzz_metric's seeds (issue 37): the well-formed ones parse, expand and
// evaluate; the hostile ones are diagnosed, naming what is wrong.
TEST(FuzzRegressions, SweepSpecAndMetricSeedsReplay) {
  const fs::path specs = kSource / "fuzz/corpus/sweep_spec",
                 metrics = kSource / "fuzz/corpus/metric";
  ASSERT_GE(inputs_in(specs).size(), 8u);
  ASSERT_GE(inputs_in(metrics).size(), 8u);
  replay_all(inputs_in(specs), fuzz::parse_sweep_spec);
  replay_all(inputs_in(metrics), fuzz::evaluate_metric_spec);
  const auto spec = [&](const char* name) { return fuzz::parse_sweep_spec(slurp(specs / name)); };
  const auto metric = [&](const char* name) {
    return fuzz::evaluate_metric_spec(slurp(metrics / name));
  };
  for (const char* ok : {"grid", "list", "normal", "uniform", "lognormal"})
    EXPECT_EQ(spec(ok), "ok") << ok;
  EXPECT_NE(spec("lognormal_overflow").find("is inf, not a finite number"), std::string::npos);
  EXPECT_NE(spec("range_overflow").find("STOP - START overflows a double"), std::string::npos);
  EXPECT_NE(spec("count_1e300").find("COUNT must be a whole number"), std::string::npos);
  for (const char* ok : {"max_abs", "named_window", "final_dotted", "drift_window",
                         "mean_parameters", "min_sqrt", "initial"})
    EXPECT_EQ(metric(ok), "ok") << ok;
  EXPECT_NE(metric("unknown_aggregate").find("unknown aggregate 'bogus'"), std::string::npos);
  EXPECT_NE(metric("unknown_name").find("'nope'"), std::string::npos) << metric("unknown_name");
}

TEST(FuzzRegressions, UrdfSeedsReplay) {
  // fuzz_urdf's seeds: the bundled robots read, the hostile ones diagnosed (number bombs, hex,
  // a cycle, a mimic joint, deep nesting, entities, a truncated file, a link that is a point mass).
  ScratchDir dir("fuzz-urdf");
  const std::string path = (dir.path() / "robot.urdf").string();
  for (const char* robot : {"panda.urdf", "ur5.urdf"})
    EXPECT_EQ(fuzz::read_urdf_bytes(slurp(kSource / "examples/robots" / robot), path), "ok");
  const auto seeds = inputs_in(kSource / "fuzz/corpus/urdf");
  ASSERT_GE(seeds.size(), 10u);
  replay_all(seeds, [&](const std::string& text) { return fuzz::read_urdf_bytes(text, path); });
  EXPECT_EQ(fuzz::read_urdf_bytes(slurp(kSource / "fuzz/corpus/urdf/two_links.urdf"), path), "ok");
  EXPECT_NE(fuzz::read_urdf_bytes(slurp(kSource / "fuzz/corpus/urdf/number_bomb.urdf"), path)
                .find("robot.urdf:"),
            std::string::npos);
}

TEST(FuzzRegressions, AHugeUrdfAngleIsALocatedErrorNotACast) {
  // fuzz_urdf, seed 1, from a clone in another folder (issue 37): rpy="0 0 1e67" reached
  // static_cast<long>(round(x / (pi/2))), undefined behaviour. It is refused, located.
  ScratchDir dir("fuzz-urdf-angle");
  const std::string path = (dir.path() / "robot.urdf").string();
  const std::string joint =
      fuzz::read_urdf_bytes(slurp(kSource / "fuzz/corpus/urdf/huge_angle.urdf"), path);
  EXPECT_NE(joint.find("robot.urdf:12"), std::string::npos) << joint;
  EXPECT_NE(joint.find("expected an angle of magnitude at most 1e+06 rad for the origin rpy of "
                       "joint 'shoulder', got 1e+67"),
            std::string::npos)
      << joint;
  // The same in an inertial origin, and at the edge: 1e6 rad itself is still an angle.
  std::string inertial = slurp(kSource / "fuzz/corpus/urdf/two_links.urdf");
  const std::string at = "<origin xyz=\"0 0 0.5\" rpy=\"0 0 0\"/>";
  ASSERT_NE(inertial.find(at), std::string::npos);
  std::string edge = inertial;
  edge.replace(edge.find(at), at.size(), "<origin xyz=\"0 0 0.5\" rpy=\"-1e6 0 0\"/>");
  EXPECT_EQ(fuzz::read_urdf_bytes(edge, path), "ok");
  inertial.replace(inertial.find(at), at.size(), "<origin xyz=\"0 0 0.5\" rpy=\"0 -1.5e6 0\"/>");
  EXPECT_NE(fuzz::read_urdf_bytes(inertial, path).find("the inertial origin rpy of link 'upper'"),
            std::string::npos);
}

TEST(FuzzRegressions, MetricFindingsAreDiagnosed) {
  const auto findings = inputs_in(kSource / "tests/hardening/data/fuzz/metric");
  ASSERT_FALSE(findings.empty());
  replay_all(findings, fuzz::evaluate_metric_spec);
}

TEST(FuzzRegressions, AComplexNumberIsALocatedErrorNotAnEscapedException) {
  // fuzz_metric, seed 1, from CI's clone (stop 45): sqrt(theta^0 + 0e30 - 2) folded to the
  // complex float 1.0*I, and the tape compiler's std::invalid_argument escaped bind_metrics.
  const std::string metric = fuzz::evaluate_metric_spec(
      slurp(kSource / "tests/hardening/data/fuzz/metric/complex-sqrt.txt"));
  EXPECT_NE(metric.find("expected a real value, got I, which is not real"), std::string::npos)
      << metric;
  // Every way a real operand leaves the real line, exact or in floating point, at the call.
  for (const char* text :
       {"sqrt(0-2)", "x + sqrt(-2.0)*y", "log(-1)", "log(-2.5)", "asin(2.0)", "acos(-3.0)",
        "(-2.0)^0.5", "(0-8)^(1/2)", "(-1)^(1/2)*x", "(-8)^(1/3)", "1e-300*sqrt(-3)"})
    EXPECT_NE(replay_expression(text).find("expected a real value"), std::string::npos)
        << text << ": " << replay_expression(text);
  // Real results of the same functions stay expressions; a sign the reader cannot know
  // (sqrt(x - 2)) is the model's business at run time.
  for (const char* text : {"sqrt(2)", "log(2.5)", "asin(0.5)", "sqrt(x - 2)", "(-2)^2", "abs(-2)"})
    EXPECT_EQ(replay_expression(text), "ok") << text;
}

TEST(FuzzRegressions, DeepNestingIsAnErrorNotAStackOverflow) {
  const std::string deep = std::string(100000, '(') + "x" + std::string(100000, ')');
  EXPECT_NE(replay_expression(deep), "ok");
  EXPECT_NE(replay_expression(std::string(100000, '-') + "x"), "ok");
  EXPECT_NE(replay_expression(std::string(100000, '[')), "ok");
  std::string powers = "x";
  for (int i = 0; i < 50000; ++i) powers += "^x";
  EXPECT_NO_THROW(replay_expression(powers));
}

}  // namespace
}  // namespace lagrange::hardening
