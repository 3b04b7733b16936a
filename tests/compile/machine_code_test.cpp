// MachineCode: tapes compiled by the system C compiler compute what eval computes, bit for bit;
// the on-disk cache is hit on the second build; and every way it cannot be had is an error that
// says why (the caller falls back to the interpreter).

#include "lagrange/machine_code.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "compile/pendulum_expressions.hpp"

namespace lagrange {
namespace {

namespace fs = std::filesystem;

/// A fresh, empty cache directory per test, removed afterwards.
class MachineCodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("lagrange-mc-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    options_.cache_dir = dir_.string();
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
  MachineCodeOptions options_;
};

/// Max over outputs and points of "not bit-identical" (NaN = NaN counts as identical).
size_t differing_outputs(const Tape& t, MachineCode::Function f,
                         const std::vector<std::vector<double>>& points) {
  std::vector<double> want(t.num_outputs()), got(t.num_outputs()), work(t.work_size() + 1);
  size_t differing = 0;
  for (const auto& x : points) {
    t.eval(x.data(), want.data(), work.data());
    f(x.data(), got.data(), work.data());
    for (size_t i = 0; i < want.size(); ++i)
      differing += !(got[i] == want[i] || (std::isnan(got[i]) && std::isnan(want[i])));
  }
  return differing;
}

TEST_F(MachineCodeTest, EveryOpIsBitIdenticalToEval) {
  GiNaC::symbol x("x"), y("y");
  const Tape t = Tape::compile(
      {-3 * x + 2 * y - 7, -x * y * 5, 1 / x, x / y, pow(x, 3) - pow(y, -2),
       pow(x * x, GiNaC::numeric(1, 3)), sqrt(y * y + 1),
       sin(x) - cos(y) * tan(x) + sin(y) * cos(x), asin(x / 2) + acos(y / 3) + atan(x), atan2(x, y),
       sinh(x) + cosh(y) + tanh(x * y), exp(x) * log(y * y) + abs(x)},
      {x, y});
  const auto code = MachineCode::build({&t}, options_);
  EXPECT_FALSE(code->from_cache());
  EXPECT_EQ(differing_outputs(t, code->function(0), {{0.3, -1.7}, {-1.1, 2.5}, {1.9, 0.01}}), 0u);
}

// Tape::to_shared_c: one library compiled for a specialisation of the pendulum (docs/theory.md
// §8) serves another set of parameter values, its constants read from the scratch array, and
// computes what that specialisation's eval computes, bit for bit; a zero parameter folds terms
// away, a structure of its own and another text. Small (one function) and split tapes.
TEST_F(MachineCodeTest, SharedCodeServesEverySpecialisationOfItsStructure) {
  for (const int n : {2, 20}) {
    const test::Pendulum p = test::make_pendulum(n);
    const Tape t = Tape::compile(p.outputs, p.inputs);
    const auto values = [&](double scale) {
      std::vector<double> v;
      for (size_t i = p.first_parameter; i < p.inputs.size(); ++i)
        v.push_back(scale * (0.7 + 0.1 * static_cast<double>(i % 7)));
      return v;
    };
    const Tape a = t.specialize(p.first_parameter, values(1.0));
    const Tape b = t.specialize(p.first_parameter, values(1.37));
    const size_t at = std::max(a.work_size(), b.work_size());
    ASSERT_EQ(a.to_shared_c("f", at), b.to_shared_c("f", at)) << n;
    std::vector<double> zero_g = values(1.0);
    zero_g.back() = 0.0;
    EXPECT_NE(t.specialize(p.first_parameter, zero_g).to_shared_c("f", at), a.to_shared_c("f", at));

    MachineCodeOptions shared = options_;
    shared.constants_at = {at};
    const auto code = MachineCode::build({&a}, shared);
    std::vector<std::vector<double>> points;
    for (unsigned seed = 0; seed < 5; ++seed) points.push_back(test::pendulum_point(n, seed));
    const std::vector<double> k = b.constants();
    std::vector<double> want(b.num_outputs()), got(b.num_outputs()), work(at + k.size());
    size_t differing = 0;
    for (const auto& x : points) {
      b.eval(x.data(), want.data(), work.data());
      std::copy(k.begin(), k.end(), work.begin() + static_cast<long>(at));
      code->function(0)(x.data(), got.data(), work.data());
      for (size_t i = 0; i < want.size(); ++i) differing += !(got[i] == want[i]);
    }
    EXPECT_EQ(differing, 0u) << n;
    EXPECT_NE(want, std::vector<double>(want.size(), 0.0));
  }
}

TEST_F(MachineCodeTest, LargeTapeKeepsItsRegistersInTheScratchArray) {
  const int n = 20;  // several 256-statement parts
  const test::Pendulum p = test::make_pendulum(n);
  const Tape t = Tape::compile(p.outputs, p.inputs);
  ASSERT_GT(t.num_instructions(), 3 * 256u);
  const auto code = MachineCode::build({&t}, options_);
  std::vector<std::vector<double>> points;
  for (unsigned seed = 0; seed < 5; ++seed) points.push_back(test::pendulum_point(n, seed));
  EXPECT_EQ(differing_outputs(t, code->function(0), points), 0u);
}

TEST_F(MachineCodeTest, SecondBuildComesFromTheCache) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({sin(x) * 2}, {x});
  const auto first = MachineCode::build({&t}, options_);
  const auto second = MachineCode::build({&t}, options_);
  EXPECT_FALSE(first->from_cache());
  EXPECT_TRUE(second->from_cache());
  EXPECT_EQ(first->path(), second->path());
  EXPECT_NE(MachineCode::cached({&t}, options_), nullptr);
  // Only the finished library and its record are left: no sources, logs or partial files.
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir_)) files.push_back(e.path().filename());
  std::sort(files.begin(), files.end());
  const std::string name = fs::path(first->path()).filename();
  EXPECT_EQ(files, (std::vector<std::string>{name, name + ".sha256"}));
  EXPECT_EQ(fs::status(dir_).permissions() & fs::perms::all, fs::perms::owner_all);
}

/// x + 1 evaluated by `code`'s first function.
double plus_one(const MachineCode& code, double x) {
  double out = 0.0, work[4];
  code.function(0)(&x, &out, work);
  return out;
}

TEST_F(MachineCodeTest, TruncatedEntryIsRecompiledSayingSo) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x + 1}, {x});
  const std::string path = MachineCode::build({&t}, options_)->path();
  fs::resize_file(path, fs::file_size(path) / 2);  // was a SIGBUS at dlopen or the first call
  std::string rejected;
  EXPECT_EQ(MachineCode::cached({&t}, options_, &rejected), nullptr);
  EXPECT_NE(rejected.find("does not match its recorded SHA-256"), std::string::npos) << rejected;
  const auto again = MachineCode::build({&t}, options_);
  EXPECT_FALSE(again->from_cache());
  EXPECT_NE(again->note().find("truncated, replaced or another model's); recompiled"),
            std::string::npos)
      << again->note();
  EXPECT_EQ(plus_one(*again, 2.0), 3.0);
  EXPECT_TRUE(MachineCode::build({&t}, options_)->from_cache());  // the entry was replaced
}

// A FIFO in place of the cached library or of its record (issue 37 item 11): once open() blocked
// for ever; now the entry is rejected at once, saying why, and replaced by a new build.
TEST_F(MachineCodeTest, AFifoInTheCacheIsRejectedNotOpened) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x + 1}, {x});
  const std::string path = MachineCode::build({&t}, options_)->path();
  for (const std::string& entry : {path, path + ".sha256"}) {
    SCOPED_TRACE(entry);
    fs::remove(entry);
    ASSERT_EQ(::mkfifo(entry.c_str(), 0600), 0);
    std::string rejected;
    EXPECT_EQ(MachineCode::cached({&t}, options_, &rejected), nullptr);
    EXPECT_NE(rejected.find("or its '.sha256' is not a regular file"), std::string::npos)
        << rejected;
    const auto again = MachineCode::build({&t}, options_);
    EXPECT_FALSE(again->from_cache());
    EXPECT_EQ(plus_one(*again, 2.0), 3.0);
    EXPECT_TRUE(fs::is_regular_file(entry));
  }
}

TEST_F(MachineCodeTest, ForeignEntryIsRecompiledSayingSo) {
  GiNaC::symbol x("x");
  const Tape mine = Tape::compile({x + 1}, {x}), other = Tape::compile({x * 10, x}, {x});
  const std::string path = MachineCode::build({&mine}, options_)->path();
  const std::string foreign = MachineCode::build({&other}, options_)->path();
  // Another model's library under this one's name: with its own record, and with a record
  // rewritten to its bytes (as an attacker who can write the directory would).
  for (const bool with_record : {true, false}) {
    SCOPED_TRACE(with_record);
    fs::copy_file(foreign, path, fs::copy_options::overwrite_existing);
    if (with_record)
      fs::copy_file(foreign + ".sha256", path + ".sha256", fs::copy_options::overwrite_existing);
    else
      fs::remove(path + ".sha256");
    std::string rejected;
    EXPECT_EQ(MachineCode::cached({&mine}, options_, &rejected), nullptr);
    EXPECT_FALSE(rejected.empty());
    const auto code = MachineCode::build({&mine}, options_);
    EXPECT_FALSE(code->from_cache());
    EXPECT_NE(code->note().find("recompiled"), std::string::npos);
    EXPECT_EQ(plus_one(*code, 2.0), 3.0);
  }
}

TEST_F(MachineCodeTest, CacheOthersCanWriteIsRefused) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x + 1}, {x});
  (void)MachineCode::build({&t}, options_);
  fs::permissions(dir_, fs::perms::all);  // 0777
  for (const bool compile : {false, true}) {
    try {
      if (compile)
        (void)MachineCode::build({&t}, options_);
      else
        (void)MachineCode::cached({&t}, options_);
      ADD_FAILURE() << "loaded code from a directory anyone can write";
    } catch (const MachineCodeError& e) {
      EXPECT_NE(std::string(e.what()).find("is writable by group or others (mode 0777)"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST_F(MachineCodeTest, TwoLibrariesInOneProcessKeepTheirOwnFunctions) {
  GiNaC::symbol x("x");
  const Tape a = Tape::compile({x + 1}, {x}), b = Tape::compile({x * 10}, {x});
  const auto ca = MachineCode::build({&a}, options_);
  const auto cb = MachineCode::build({&a, &b}, options_);
  double in = 2.0, out = 0.0, work[4];
  ca->function(0)(&in, &out, work);
  EXPECT_EQ(out, 3.0);
  cb->function(1)(&in, &out, work);
  EXPECT_EQ(out, 20.0);
  EXPECT_EQ(MachineCode::cached({&b}, options_), nullptr);  // a different library
}

TEST_F(MachineCodeTest, MissingCompilerSaysSo) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x}, {x});
  options_.compiler = "no-such-compiler-for-lagrange";
  try {
    (void)MachineCode::build({&t}, options_);
    FAIL() << "expected MachineCodeError";
  } catch (const MachineCodeError& e) {
    EXPECT_NE(
        std::string(e.what()).find("no C compiler: 'no-such-compiler-for-lagrange' is not on PATH"),
        std::string::npos)
        << e.what();
  }
}

TEST_F(MachineCodeTest, UnwritableCacheSaysSo) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x}, {x});
  options_.cache_dir = "/proc/self/lagrange-cache";  // not creatable, even by root
  try {
    (void)MachineCode::build({&t}, options_);
    FAIL() << "expected MachineCodeError";
  } catch (const MachineCodeError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the machine-code cache directory"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(MachineCodeTest, FullDiskSaysSoAndLeavesNothingBehind) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({sin(x) + cos(x)}, {x});
  // A file-size limit of 16 bytes makes every write fail as on a full disk (EFBIG, with
  // SIGXFSZ ignored), in this process and in the compiler it starts.
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 16;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string what;
  try {
    (void)MachineCode::build({&t}, options_);
  } catch (const MachineCodeError& e) {
    what = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_NE(what.find("cannot write"), std::string::npos) << what;
  EXPECT_NE(what.find("machine-code cache"), std::string::npos) << what;
  for (const auto& e : fs::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << e.path();
}

/// An executable shell script standing in for the compiler.
std::string fake_compiler(const fs::path& dir, const std::string& body) {
  fs::create_directories(dir);
  const fs::path path = dir / "fake-cc";
  std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(path, fs::perms::owner_all);
  return path.string();
}

TEST_F(MachineCodeTest, FailingCompilerReportsItsOutput) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x}, {x});
  options_.compiler = fake_compiler(dir_ / "bin", "echo 'disk quota exceeded' >&2; exit 1");
  try {
    (void)MachineCode::build({&t}, options_);
    FAIL() << "expected MachineCodeError";
  } catch (const MachineCodeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("failed (exit 1)"), std::string::npos) << what;
    EXPECT_NE(what.find("disk quota exceeded"), std::string::npos) << what;
  }
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_TRUE(e.is_directory()) << "left behind: " << e.path();
}

TEST_F(MachineCodeTest, CancelStopsARunningCompiler) {
  GiNaC::symbol x("x");
  const Tape t = Tape::compile({x}, {x});
  options_.compiler = fake_compiler(dir_ / "bin", "sleep 30");
  std::atomic<bool> cancel{false};
  options_.cancel = &cancel;
  std::thread stopper([&cancel] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancel = true;
  });
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW((void)MachineCode::build({&t}, options_), MachineCodeError);
  stopper.join();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

}  // namespace
}  // namespace lagrange
