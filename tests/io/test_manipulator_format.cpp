// `derive --form manipulator` of an arm too large to write out (src/io/manipulator_format.cpp):
// the Panda is printed through named common subexpressions, and what is printed evaluates to
// the same D, Christoffel symbols and g as the form itself (issue 20: 25 MB before).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lagrange/io.hpp"
#include "lagrange/manipulator.hpp"
#include "support/harness.hpp"
#include "symbolic/point_value.hpp"

namespace lagrange {
namespace {

using testing::example_path;

/// The printed expression `text` evaluated with `table` (coordinates, velocities, parameters
/// and the subexpressions defined so far as numbers); unknown names are an error.
double printed_value(GiNaC::parser& reader, const std::string& text) {
  const GiNaC::ex v = reader(text).evalf();
  EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(v)) << text;
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

TEST(ManipulatorFormat, PandaPrintsSharedSubexpressionsThatEvaluateToTheForm) {
  const Model m = read_model_file(example_path("robots/panda.urdf"));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  const std::string json = format_manipulator(f, "json");
  EXPECT_LT(json.size(), 2'000'000u);  // written out in full it is 25 MB
  const nlohmann::json j = nlohmann::json::parse(json);
  ASSERT_TRUE(j.contains("subexpressions")) << "the Panda's form is printed in full";
  EXPECT_NE(format_manipulator(f, "text").find("named common"), std::string::npos);

  GiNaC::symtab table;
  GiNaC::exmap at;
  for (size_t i = 0; i < eq.nv; ++i) {
    const GiNaC::numeric q(0.3 + 0.17 * static_cast<double>(i)),
        v(-0.8 + 0.31 * static_cast<double>(i));
    table[eq.kin.q[i].get_name()] = q;
    table[eq.kin.v[i].get_name()] = v;
    at[eq.kin.q[i]] = q;
    at[eq.kin.v[i]] = v;
  }
  for (const Parameter& p : m.parameters) {
    table[p.name] = GiNaC::numeric(p.value);
    at[p.sym] = GiNaC::numeric(p.value);
  }
  at[m.t] = 0;
  GiNaC::parser reader(table, true);
  for (const auto& def : j["subexpressions"])
    reader.get_syms()[def[0].get<std::string>()] = printed_value(reader, def[1].get<std::string>());

  symbolic::PointValue exact(at);
  auto expect_same = [&](const std::string& printed, const GiNaC::ex& e, const std::string& what) {
    const double want = exact(e).to_double();
    EXPECT_NEAR(printed_value(reader, printed), want, 1e-12 * (1 + std::abs(want))) << what;
  };
  for (size_t i = 0; i < eq.nv; ++i) {
    for (size_t k = 0; k < eq.nv; ++k)
      expect_same(j["D"][i][k], f.D(i, k), "D_" + std::to_string(i + 1) + std::to_string(k + 1));
    expect_same(j["g"][i], f.g[i], "g_" + std::to_string(i + 1));
  }
  ASSERT_EQ(j["christoffel"].size(), f.christoffel.size());
  for (size_t n = 0; n < f.christoffel.size(); ++n)
    expect_same(j["christoffel"][n]["value"], f.christoffel[n].value, "c #" + std::to_string(n));
}

// A small arm stays written out in full (the seed's elbow: the entries are expressions of q).
TEST(ManipulatorFormat, SmallArmIsWrittenOutInFull) {
  const Model m = read_model_file(example_path("elbow_manipulator.yaml"));
  const Equations eq = derive(m);
  const std::string text = format_manipulator(manipulator_form(eq), "text");
  EXPECT_EQ(text.find("named common"), std::string::npos);
  EXPECT_NE(text.find("cos(q2)"), std::string::npos) << text;
}

}  // namespace
}  // namespace lagrange
