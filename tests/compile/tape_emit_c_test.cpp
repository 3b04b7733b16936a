// Tape::to_c: the emitted C, compiled by the system C compiler, computes what eval computes.

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "compile/pendulum_expressions.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace {

using Fn = void (*)(const double*, double*);

/// A shared library built from C source with `cc -O1`, opened with dlopen; closed on scope exit.
class CompiledC {
 public:
  /// Writes `source` into a fresh temp directory, compiles it and looks up `name`.
  CompiledC(const std::string& source, const std::string& name) {
    char tmpl[] = "/tmp/lagrange_tape_XXXXXX";
    const char* dir = mkdtemp(tmpl);
    if (dir == nullptr) throw std::runtime_error("mkdtemp failed");
    dir_ = dir;
    std::ofstream(dir_ / "tape.c") << source;
    const std::string cmd = "cc -std=c99 -O1 -ffp-contract=off -shared -fPIC -o '" +
                            (dir_ / "tape.so").string() + "' '" + (dir_ / "tape.c").string() +
                            "' -lm 2> '" + (dir_ / "cc.log").string() + "'";
    if (std::system(cmd.c_str()) != 0) {
      std::ifstream log(dir_ / "cc.log");
      throw std::runtime_error("C compiler failed: " +
                               std::string(std::istreambuf_iterator<char>(log), {}));
    }
    handle_ = dlopen((dir_ / "tape.so").c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_ == nullptr) throw std::runtime_error(dlerror());
    fn_ = reinterpret_cast<Fn>(dlsym(handle_, name.c_str()));
    if (fn_ == nullptr) throw std::runtime_error("symbol not found: " + name);
  }
  ~CompiledC() {
    if (handle_ != nullptr) dlclose(handle_);
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  CompiledC(const CompiledC&) = delete;
  CompiledC& operator=(const CompiledC&) = delete;

  /// Calls the compiled function.
  void operator()(const double* in, double* out) const { fn_(in, out); }

 private:
  std::filesystem::path dir_;
  void* handle_ = nullptr;
  Fn fn_ = nullptr;
};

/// Asserts that the compiled C of `t` equals t.eval at `points` (bit-identical expected).
void expect_c_matches_eval(const Tape& t, const std::vector<std::vector<double>>& points) {
  const CompiledC c(t.to_c("tape_fn"), "tape_fn");
  std::vector<double> want(t.num_outputs()), got(t.num_outputs()), work(t.work_size());
  size_t identical = 0, total = 0;
  for (const auto& x : points) {
    t.eval(x.data(), want.data(), work.data());
    c(x.data(), got.data());
    for (size_t i = 0; i < want.size(); ++i) {
      EXPECT_NEAR(got[i], want[i], 1e-14 * std::max(1.0, std::fabs(want[i]))) << "output " << i;
      identical += got[i] == want[i] || (std::isnan(got[i]) && std::isnan(want[i]));
      ++total;
    }
  }
  EXPECT_EQ(identical, total) << "outputs not bit-identical to eval";
}

TEST(TapeEmitC, PendulumMatchesEval) {
  const int n = 10;
  const test::Pendulum p = test::make_pendulum(n);
  const Tape t = Tape::compile(p.outputs, p.inputs);
  std::vector<std::vector<double>> points;
  for (unsigned seed = 0; seed < 5; ++seed) points.push_back(test::pendulum_point(n, seed));
  expect_c_matches_eval(t, points);
  const std::vector<double> params(points[0].begin() + p.first_parameter, points[0].end());
  expect_c_matches_eval(t.specialize(p.first_parameter, params), points);
}

TEST(TapeEmitC, EveryOpMatchesEval) {
  GiNaC::symbol x("x"), y("y");
  const std::vector<GiNaC::ex> outs = {-3 * x + 2 * y - 7,
                                       -x * y * 5,
                                       -x,
                                       1 / x,
                                       x / y,
                                       pow(x, 3) - pow(y, -2),
                                       pow(x * x, GiNaC::numeric(1, 3)),
                                       sqrt(y * y + 1),
                                       sin(x) - cos(y) * tan(x),
                                       asin(x / 2) + acos(y / 3) + atan(x),
                                       atan2(x, y),
                                       sinh(x) + cosh(y) + tanh(x * y),
                                       exp(x) * log(y * y) + abs(x),
                                       GiNaC::ex(1) / 3 + x * 1e-300,
                                       pow(x, -7)};
  const Tape t = Tape::compile(outs, {x, y});
  expect_c_matches_eval(t, {{0.3, -1.7}, {-1.1, 2.5}, {1.9, 0.01}});
}

TEST(TapeEmitC, SourceIsSelfContainedC99) {
  GiNaC::symbol x("x");
  const std::string c = Tape::compile({sin(x) + 2}, {x}).to_c("my_fn");
  EXPECT_NE(c.find("#include <math.h>"), std::string::npos);
  EXPECT_NE(c.find("void my_fn(const double* in, double* out)"), std::string::npos);
  EXPECT_EQ(c.find("#include", c.find("#include") + 1), std::string::npos);
  EXPECT_THROW(Tape::compile({x}, {x}).to_c("not a name"), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
