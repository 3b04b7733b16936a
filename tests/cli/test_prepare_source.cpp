// What the Python module calls before a run (src/cli/prepare.hpp): prepare_source reads a model
// from a file or from text exactly as `lagrange simulate` does, blames the caller's values for
// what the file alone does not have, and simulation_options / choose_evaluation apply settings.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/error.hpp"
#include "support/file_text.hpp"
#include "support/test_paths.hpp"

namespace lagrange::cli {
namespace {

const std::string kPendulum = std::string(LAGRANGE_SOURCE_DIR) + "/examples/pendulum.yaml";

Trajectory run(Prepared& p, double t_end) {
  SimulationOptions so = simulation_options(*p.model, RunSettings{t_end, {}, {}, {}, {}, {}, {}});
  return simulate(*p.dynamics, so, p.q, p.v);
}

TEST(PrepareSource, TextAndFileGiveTheSameRunAsPrepare) {
  Prepared cli = prepare(kPendulum, {"l=1.5"}, {}, "--initial", "auto");
  Prepared file = prepare_source(ModelSource{kPendulum, std::nullopt}, {{"l", 1.5}});
  Prepared text = prepare_source(ModelSource{kPendulum, test::slurp(kPendulum)}, {{"l", 1.5}});
  EXPECT_EQ(text.model->file, kPendulum);
  const Trajectory a = run(cli, 1.0), b = run(file, 1.0), c = run(text, 1.0);
  ASSERT_EQ(a.rows(), 101u);
  EXPECT_EQ(a.data, b.data);  // bit for bit
  EXPECT_EQ(a.data, c.data);
  // l = 1.5 reached the run
  Prepared plain = prepare(kPendulum, {});
  EXPECT_NE(a.data.back(), run(plain, 1.0).data.back());
}

TEST(PrepareSource, TextMistakesKeepTheLabelAndLocation) {
  try {
    prepare_source(ModelSource{"mine.yaml",
                               "name: x\ncoordinates:\n  x: {initial: 1}\n"
                               "kinetic: der(x)^2/2\npotential: x +* 2\n"},
                   {});
    FAIL() << "no ModelError";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().file, "mine.yaml");
    EXPECT_EQ(e.loc().line, 5);
    EXPECT_GT(e.loc().column, 0);
  }
}

TEST(PrepareSource, TheCallersValuesAreBlamedAsSet) {
  try {
    prepare_source(ModelSource{kPendulum, std::nullopt}, {{"nope", 1.0}});
    FAIL() << "no UsageError";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("set: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
  }
  try {  // a negative mass: the file alone is fine, so the value is the caller's mistake
    prepare_source(ModelSource{kPendulum, std::nullopt}, {{"m", -1.0}});
    FAIL() << "no UsageError";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("set m=-1: the model does not accept this value", 0), 0u)
        << e.what();
  }
}

TEST(SimulationOptions, GivenValuesReplaceTheFilesAndAreChecked) {
  Prepared p = prepare(kPendulum, {});
  const SimulationOptions file = simulation_options(*p.model, RunSettings{});
  EXPECT_EQ(file.t_end, 10.0);
  EXPECT_EQ(file.integrator.rtol, 1e-10);
  EXPECT_EQ(file.integrator.max_order, 5);
  const SimulationOptions given =
      simulation_options(*p.model, RunSettings{2.0, 0.5, 1e-6, {}, {}, std::string("rk4"), 3});
  EXPECT_EQ(given.t_end, 2.0);
  EXPECT_EQ(given.output_step, 0.5);
  EXPECT_EQ(given.integrator.rtol, 1e-6);
  EXPECT_EQ(given.integrator.atol, 1e-12);
  EXPECT_EQ(given.integrator.method, "rk4");
  EXPECT_EQ(given.integrator.max_order, 3);
  EXPECT_THROW(simulation_options(*p.model, RunSettings{-1.0, {}, {}, {}, {}, {}, {}}), UsageError);
  EXPECT_THROW(simulation_options(*p.model, RunSettings{{}, {}, 0.0, {}, {}, {}, {}}), UsageError);
  EXPECT_THROW(simulation_options(*p.model, RunSettings{{}, {}, {}, {}, {}, {}, 0}), UsageError);
}

TEST(ChooseEvaluation, OffKeepsTheInterpreterAndUnknownWordsAreRejected) {
  Prepared p = prepare(kPendulum, {});
  EXPECT_TRUE(choose_evaluation(*p.dynamics, "off"));
  EXPECT_FALSE(p.dynamics->uses_machine_code());
  EXPECT_THROW(choose_evaluation(*p.dynamics, "sometimes"), UsageError);
}

}  // namespace
}  // namespace lagrange::cli
