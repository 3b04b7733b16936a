// libFuzzer target: a whole URDF file → read_model_file (the path `lagrange check robot.urdf`
// takes: XML, numbers, joint tree, links lowered into bodies), then derive + compile when the
// robot is small (urdf_input.hpp). Any ModelError is a correct answer; every other exception,
// crash, sanitizer report, hang or runaway allocation is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "urdf_input.hpp"

namespace {

constexpr size_t kMaxInput = 16384;  // the bundled robots are 6–8 KB

// The reader takes URDF from a file: one per process in a directory of its own, rewritten for
// each input and removed at exit. fuzz/run.sh names a fixed directory (FUZZ_URDF_DIR) for its
// fixed-seed runs: mkdtemp's random name would reach the reader's messages and comparisons, and
// with them the inputs libFuzzer derives, so no two runs would explore alike.
std::string directory;

void remove_directory() {
  std::filesystem::remove_all(directory);
}

const std::string& input_path() {
  static const std::string path = [] {
    if (const char* fixed = std::getenv("FUZZ_URDF_DIR")) {
      directory = fixed;
      std::filesystem::create_directories(directory);
    } else {
      directory =
          std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/fuzz_urdf.XXXXXX";
      if (mkdtemp(directory.data()) == nullptr) std::abort();
    }
    std::atexit(remove_directory);
    return directory + "/robot.urdf";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInput) return -1;  // reject: not added to the corpus
  (void)lagrange::fuzz::read_urdf_bytes(std::string(reinterpret_cast<const char*>(data), size),
                                        input_path());
  return 0;
}
