// Tape::to_text: the named-common-subexpression text that `derive` prints for large models reads
// back (through GiNaC's parser) to the same values as the tape, names each shared value once and
// grows with the tape.

#include <gtest/gtest.h>

#include <random>
#include <regex>
#include <set>

#include "compile/pendulum_expressions.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace {

// The text's outputs as numbers: definitions are parsed in order and substituted into what
// follows, inputs take the values x.
std::vector<double> read_back(const Tape::Text& text, const std::vector<GiNaC::symbol>& inputs,
                              const std::vector<double>& x) {
  GiNaC::symtab table;
  GiNaC::exmap values;
  for (size_t i = 0; i < inputs.size(); ++i) {
    table[inputs[i].get_name()] = inputs[i];
    values[inputs[i]] = GiNaC::numeric(x[i]);
  }
  GiNaC::parser reader(table, true);
  for (const auto& [name, expr] : text.definitions) {
    const GiNaC::ex value = reader(expr).subs(values).evalf();
    EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(value)) << name << " = " << expr;
    const GiNaC::symbol s(name);
    reader.get_syms()[name] = s;
    values[s] = value;
  }
  std::vector<double> out;
  for (const auto& expr : text.outputs)
    out.push_back(GiNaC::ex_to<GiNaC::numeric>(reader(expr).subs(values).evalf()).to_double());
  return out;
}

TEST(TapeText, ReadsBackToTheTapeValues) {
  const test::Pendulum p = test::make_pendulum(4);
  const Tape tape = Tape::compile(p.outputs, p.inputs);
  std::vector<std::string> names;
  for (const auto& s : p.inputs) names.push_back(s.get_name());
  const Tape::Text text = tape.to_text(names);
  ASSERT_EQ(text.outputs.size(), tape.num_outputs());
  EXPECT_GT(text.definitions.size(), 10u);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 1.5);
  std::vector<double> x(p.inputs.size());
  for (double& v : x) v = u(rng);
  std::vector<double> expected(tape.num_outputs()), work(tape.work_size());
  tape.eval(x.data(), expected.data(), work.data());
  const std::vector<double> got = read_back(text, p.inputs, x);
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(got[i], expected[i], 1e-12 * (1 + std::abs(expected[i]))) << text.outputs[i];
}

TEST(TapeText, NamesEachSharedValueOnceBeforeItsUse) {
  const test::Pendulum p = test::make_pendulum(6);
  const Tape tape = Tape::compile(p.outputs, p.inputs);
  std::vector<std::string> names;
  for (const auto& s : p.inputs) names.push_back(s.get_name());
  const Tape::Text text = tape.to_text(names, "z");
  std::set<std::string> defined;
  const std::regex name(R"(\bz\d+\b)");
  auto check_uses = [&](const std::string& expr) {
    for (auto it = std::sregex_iterator(expr.begin(), expr.end(), name);
         it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(defined.count(it->str())) << it->str() << " used before it is defined";
  };
  size_t chars = 0;
  for (size_t k = 0; k < text.definitions.size(); ++k) {
    const auto& [lhs, rhs] = text.definitions[k];
    EXPECT_EQ(lhs, "z" + std::to_string(k + 1));
    check_uses(rhs);
    defined.insert(lhs);
    chars += rhs.size();
  }
  for (const auto& o : text.outputs) {
    check_uses(o);
    chars += o.size();
  }
  // Linear in the tape: a bounded number of characters per instruction.
  EXPECT_LT(chars, 60 * tape.num_instructions());
  EXPECT_THROW(tape.to_text({"too", "few"}), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
