// Determinism within one process (issue 8, item 10): every example derived after all the others
// (fresh symbols, created later and in another order) compiles to the same tapes, instruction
// for instruction, and integrates to a bit-identical trajectory. GiNaC orders terms by hashes of
// symbol serial numbers, so this fails when a tape is built in GiNaC's order.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>

#include "support/harness.hpp"

namespace lagrange {
namespace {

/// What must not depend on which models were derived earlier in the process.
struct Fingerprint {
  std::string dynamics, observables, inputs;  ///< the tapes as C, one statement per instruction
  std::vector<double> trajectory;             ///< one second of the model's own simulation
};

Fingerprint fingerprint(const std::string& file) {
  auto sys = testing::load_example(file);
  Fingerprint f{sys.compiled->dynamics.to_c("dynamics"),
                sys.compiled->observables.to_c("observables"),
                sys.compiled->inputs.to_c("inputs"),
                {}};
  SimulationOptions so = sys.options();
  so.t_end = std::min(so.t_end, 1.0);
  f.trajectory = sys.run(so).data;
  return f;
}

TEST(TapeOrder, SameTapesWhicheverModelsCameFirst) {
  const std::vector<std::string> names = testing::example_files();
  ASSERT_GE(names.size(), 2u);
  std::map<std::string, Fingerprint> first;
  for (const auto& name : names) first.emplace(name, fingerprint(name));
  for (auto it = names.rbegin(); it != names.rend(); ++it) {
    const Fingerprint again = fingerprint(*it);
    const Fingerprint& before = first.at(*it);
    EXPECT_TRUE(again.dynamics == before.dynamics) << *it << ": dynamics tape differs";
    EXPECT_TRUE(again.observables == before.observables) << *it << ": observables tape differs";
    EXPECT_TRUE(again.inputs == before.inputs) << *it << ": inputs tape differs";
    ASSERT_EQ(again.trajectory.size(), before.trajectory.size()) << *it;
    EXPECT_EQ(std::memcmp(again.trajectory.data(), before.trajectory.data(),
                          before.trajectory.size() * sizeof(double)),
              0)
        << *it << ": trajectory differs";
  }
}

}  // namespace
}  // namespace lagrange
