// The trajectory CSV and its sidecar never disagree (issue 25 item 1): concurrent writers to
// one -o, SIGKILL during the write, a full disk and an unwritable location each leave either
// the old pair, the new pair, or a CSV without a sidecar — never a sidecar describing a file
// that is not there — and no temporary file once a later run has cleaned up.

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>

#include <map>
#include <nlohmann/json.hpp>

#include "support/test_paths.hpp"
#include "hardening/cli_runner.hpp"

namespace lagrange::hardening {
namespace {

using lagrange::test::example_path;

std::vector<std::string> simulate(const fs::path& csv, const std::string& t_end,
                                  const std::string& step = "0.01") {
  return {"simulate",
          example_path("pendulum.yaml"),
          "-o",
          csv.string(),
          "--t-end",
          t_end,
          "--output-step",
          step,
          "--compile",
          "off",
          "-q"};
}

/// Size of `path` in bytes, -1 when it does not exist.
long long size_of(const fs::path& path) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  return ec ? -1 : static_cast<long long>(n);
}

/// The sidecar's record of the CSV's size (-1 without a sidecar).
long long recorded_size(const fs::path& csv) {
  const std::string text = slurp(csv.string() + ".json");
  if (text.empty()) return -1;
  return nlohmann::json::parse(text).at("csv_bytes").get<long long>();
}

/// Names in `dir` ending in ".part".
std::vector<std::string> parts_in(const ScratchDir& dir) {
  std::vector<std::string> parts;
  for (const auto& name : dir.files())
    if (name.size() > 5 && name.compare(name.size() - 5, 5, ".part") == 0) parts.push_back(name);
  return parts;
}

/// A sidecar, when present, describes the CSV present: its size and number of rows.
void expect_truthful_pair(const fs::path& csv) {
  const long long recorded = recorded_size(csv);
  if (recorded < 0) return;
  EXPECT_EQ(recorded, size_of(csv)) << "the sidecar describes another file";
  const std::string text = slurp(csv);
  const auto rows = nlohmann::json::parse(slurp(csv.string() + ".json")).at("rows").get<long>();
  EXPECT_EQ(static_cast<long>(std::count(text.begin(), text.end(), '\n')), rows + 1);
}

TEST(OutputFiles, ConcurrentWritersEachLeaveATruthfulPair) {
  ScratchDir dir("concurrent-writers");
  const fs::path csv = dir.path() / "out.csv", log_a = dir.path() / "a", log_b = dir.path() / "b";
  fs::create_directory(log_a);
  fs::create_directory(log_b);
  for (int trial = 0; trial < 3; ++trial) {
    Child a(log_a, simulate(csv, "3")), b(log_b, simulate(csv, "5"));
    EXPECT_EQ(a.wait(std::chrono::seconds(60)).exit_code, 0);
    EXPECT_EQ(b.wait(std::chrono::seconds(60)).exit_code, 0);
    ASSERT_GT(recorded_size(csv), 0);
    expect_truthful_pair(csv);
    EXPECT_EQ(parts_in(dir), std::vector<std::string>{});
  }
}

TEST(OutputFiles, KillDuringALongWriteNeverLeavesAMismatch) {
  ScratchDir dir("kill-during-write");
  const fs::path csv = dir.path() / "out.csv";
  ASSERT_EQ(run_lagrange(dir.path(), simulate(csv, "1")).exit_code, 0);
  const long long old_size = size_of(csv);
  // One full long run (100 000 rows, ~15 MB) to time it and to know the new file's size.
  const fs::path full = dir.path() / "full.csv";
  const RunResult timed = run_lagrange(dir.path(), simulate(full, "20", "0.0002"));
  ASSERT_EQ(timed.exit_code, 0) << timed.err;
  const long long new_size = size_of(full);
  fs::remove(full);
  fs::remove(full.string() + ".json");
  // Kills spread over the run, dense towards its end where the files are written.
  for (const double at : {0.3, 0.6, 0.8, 0.9, 0.95, 1.0}) {
    SCOPED_TRACE(at);
    Child child(dir.path(), simulate(csv, "20", "0.0002"));
    std::this_thread::sleep_for(std::chrono::duration<double>(at * timed.seconds));
    child.signal(SIGKILL);
    child.wait();
    const long long now = size_of(csv);
    EXPECT_TRUE(now == old_size || now == new_size) << "a partial CSV under the final name";
    expect_truthful_pair(csv);
  }
  // The next run removes what the killed ones left.
  ASSERT_EQ(run_lagrange(dir.path(), simulate(csv, "1")).exit_code, 0);
  EXPECT_EQ(parts_in(dir), std::vector<std::string>{});
  expect_truthful_pair(csv);
}

TEST(OutputFiles, UnwritableLocationFailsBeforeTheRun) {
  ScratchDir dir("unwritable");
  spit(dir.path() / "file", "x");
  std::vector<fs::path> places{dir.path() / "file" / "out.csv", "/proc/self/out.csv"};
  if (geteuid() != 0) {  // root writes read-only directories anyway
    fs::create_directory(dir.path() / "ro");
    chmod((dir.path() / "ro").c_str(), 0500);
    places.push_back(dir.path() / "ro" / "out.csv");
  }
  for (const fs::path& csv : places) {
    SCOPED_TRACE(csv.string());
    // A long run: failing before it means failing at once.
    const RunResult r = run_lagrange(dir.path(), simulate(csv, "2000", "0.0002"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("lagrange: -o: cannot "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(csv.filename().string()), std::string::npos) << r.err;
    EXPECT_LT(r.seconds, 5.0);
  }
}

/// The type of the entry at `path` (links not followed).
fs::file_type type_of(const fs::path& path) {
  std::error_code ec;
  return fs::symlink_status(path, ec).type();
}

// An output path that exists and is not a regular file (issue 37 item 1): a FIFO, a socket, a
// directory and, as root, a device node made here are refused before the run, exit 2 naming the
// option and what the entry is, for -o, its .json sidecar, --report and `report -o`; each entry
// is left as it was and nothing is written. Before, the CSV was renamed over it (as root,
// `simulate -o /dev/null` replaced the system's /dev/null by a regular file). /dev/null itself
// is only looked at: still a character device after the refused runs.
TEST(OutputFiles, AnEntryThatIsNotARegularFileIsRefusedAndKept) {
  ScratchDir dir("special-entries");
  const fs::path& d = dir.path();
  std::vector<std::pair<std::string, std::string>> entries{
      {"fifo", "a FIFO"}, {"folder", "a directory"}, {"socket", "a socket"}};
  ASSERT_EQ(mkfifo((d / "fifo.csv").c_str(), 0644), 0);
  ASSERT_EQ(mkfifo((d / "fifo.html").c_str(), 0644), 0);
  ASSERT_EQ(mkfifo((d / "plain.csv.json").c_str(), 0644), 0);
  fs::create_directory(d / "folder.csv");
  fs::create_directory(d / "folder.html");
  for (const char* name : {"socket.csv", "socket.html"}) {
    const int s = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string path = (d / name).string();
    ASSERT_LT(path.size(), sizeof address.sun_path);
    std::copy(path.begin(), path.end(), address.sun_path);
    ASSERT_EQ(bind(s, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0) << path;
    close(s);  // the entry stays
  }
  // A private null device, where the container lets root make one (never /dev/null itself).
  if (geteuid() == 0 && mknod((d / "device.csv").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0 &&
      mknod((d / "device.html").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0)
    entries.emplace_back("device", "a character device");
  const std::vector<std::string> before = dir.files();
  std::map<std::string, fs::file_type> types;
  for (const auto& name : before) types[name] = type_of(d / name);

  const auto refused = [&](std::vector<std::string> args, const std::string& option,
                           const fs::path& entry, const std::string& kind) {
    SCOPED_TRACE(entry.string());
    const RunResult r = run_lagrange(d, args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("lagrange: " + option + ": cannot write '" + entry.string() +
                         "': it exists and is " + kind + ", not a regular file"),
              std::string::npos)
        << r.err;
    EXPECT_LT(r.seconds, 5.0);  // before the long run
    EXPECT_EQ(dir.files(), before);
    for (const auto& [name, type] : types) EXPECT_EQ(type_of(d / name), type) << name;
  };
  for (const auto& [stem, kind] : entries) {
    const fs::path csv = d / (stem + ".csv"), html = d / (stem + ".html");
    refused(simulate(csv, "2000", "0.0002"), "-o", csv, kind);
    std::vector<std::string> report = simulate(d / "plain.csv", "2000", "0.0002");
    report[3] = html.string();  // the -o value becomes --report's
    report[2] = "--report";
    refused(report, "--report", html, kind);
    refused({"report", example_path("pendulum.yaml"), (d / "missing.csv").string(), "-o",
             html.string()},
            "-o", html, kind);
  }
  refused(simulate(d / "plain.csv", "2000", "0.0002"), "-o", d / "plain.csv.json", "a FIFO");
  struct stat null_device {};
  ASSERT_EQ(stat("/dev/null", &null_device), 0);
  EXPECT_TRUE(S_ISCHR(null_device.st_mode)) << "/dev/null is no longer a character device";
}

/// A 64 KiB tmpfs at `at` (made), unmounted by the destructor; mounted() is false where the
/// machine does not let this process mount one (not root, or no CAP_SYS_ADMIN).
class SmallDisk {
 public:
  explicit SmallDisk(const fs::path& at) : at_(at) {
    fs::create_directory(at_);
    mounted_ = mount("tmpfs", at_.c_str(), "tmpfs", 0, "size=64k") == 0;
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  ~SmallDisk() {
    if (mounted_) umount2(at_.c_str(), MNT_DETACH);
  }
  bool mounted() const { return mounted_; }

 private:
  fs::path at_;
  bool mounted_ = false;
};

TEST(OutputFiles, FullDiskSaysSoAndKeepsTheOldPair) {
  ScratchDir dir("full-disk");
  const fs::path mnt = dir.path() / "small";
  const SmallDisk disk(mnt);
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  const fs::path csv = mnt / "out.csv";
  ASSERT_EQ(run_lagrange(dir.path(), simulate(csv, "1")).exit_code, 0);
  const std::string old_csv = slurp(csv), old_sidecar = slurp(csv.string() + ".json");
  const RunResult r = run_lagrange(dir.path(), simulate(csv, "10", "0.001"));  // ~1.5 MB
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write '" + csv.string() + "': no space left on device"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(csv), old_csv);
  EXPECT_EQ(slurp(csv.string() + ".json"), old_sidecar);
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(mnt)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"out.csv", "out.csv.json"}));
}

// A study's summary filling the disk (issue 37 item 16): the row cut short by the full disk is
// reported with the reason, not with a stale errno ("cannot append a row: No such file or
// directory").
TEST(OutputFiles, AStudyOnAFullDiskSaysSo) {
  ScratchDir dir("full-disk-study");
  const SmallDisk disk(dir.path() / "small");
  if (!disk.mounted()) GTEST_SKIP() << "cannot mount a tmpfs here: " << std::strerror(errno);
  const RunResult r =
      run_lagrange(dir.path(), {"sweep", example_path("pendulum.yaml"), "--vary", "m=1:2:3000",
                                "--t-end", "0.01", "--compile", "off", "-j", "1", "-q", "-o",
                                (dir.path() / "small" / "study").string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lagrange::hardening
