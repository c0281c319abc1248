// Output safety (docs/outputs.md, "How files are written"): a run or a sweep never empties a
// folder that is not its own, finds an unwritable destination before simulating, and on a
// failed write (a full disk) publishes nothing and leaves no partial copy. The full-disk and
// read-only cases mount a small tmpfs or a read-only bind mount in a private mount namespace
// (root only); elsewhere they are skipped with a visible warning.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scenarios/output/output_file.hpp"
#include "scenarios/run/run_directory.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
using masnet::test::slurp;
namespace fs = std::filesystem;

namespace {

const std::string kMasnet = std::string(MASNET_BINARY_DIR) + "/scenarios/masnet";
const std::string kAcoustic =
    std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml";
// One simulated second, two snapshots: every output file, figures and report, in about 1 s.
const std::string kShort = "--set duration=1 --set 'output.snapshots=[0.5,1]'";

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// A scratch folder of its own, removed at the end.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& tag) {
    dir = fs::temp_directory_path() / fmt::format("masnet-safety-{}-{}", tag, ::getpid());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  // Runs `command` in this folder with sh; both streams captured.
  Outcome shell(const std::string& command) const {
    const fs::path log = dir / ".log";
    const int status = std::system(
        fmt::format("cd '{}' && ( {} ) > '{}' 2>&1", dir.string(), command, log.string()).c_str());
    Outcome o;
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    o.output = slurp(log);
    fs::remove(log);
    return o;
  }
  void touch(const std::string& name) const {
    std::ofstream(dir / name) << "the user's own file\n";
  }
};

std::string run_command(const std::string& out, const std::string& extra = "") {
  return fmt::format("'{}' run '{}' {} --quiet --out {} {}", kMasnet, kAcoustic, kShort, out,
                     extra);
}

// Mounting needs root and a kernel that lets this process make a mount namespace.
bool can_mount() {
  static const int ok = std::system(
                            "unshare -m sh -c 'mount -t tmpfs -o size=64k tmpfs /mnt' "
                            "> /dev/null 2>&1") == 0;
  return ok;
}

}  // namespace

TEST_CASE("A run directory given with a trailing slash is the same directory", "[scenarios]") {
  Scratch s("slash");
  const Outcome first = s.shell(run_command("out/"));
  REQUIRE(first.exit_code == 0);
  REQUIRE(fs::exists(s.dir / "out" / "summary.json"));
  // The same run again, with the slash: replaced in place, never deleted.
  const Outcome second = s.shell(run_command("out/"));
  CHECK(second.exit_code == 0);
  CHECK(fs::exists(s.dir / "out" / "summary.json"));
  CHECK(fs::exists(s.dir / "out" / "report.html"));
  // Nothing else is left beside it (no staging or replaced copy).
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(s.dir))
    entries += e.path().filename() == "out" ? 0 : 1;
  CHECK(entries == 0);
}

TEST_CASE(
    "The working directory, its ancestors, the root and the home folder are never run directories",
    "[scenarios]") {
  Scratch s("forbidden");
  fs::create_directories(s.dir / "work");
  s.touch("work/notes.txt");
  const std::string cd = "cd work && ";
  const auto refused = [&](const std::string& out, const std::string& message) {
    const Outcome o = s.shell(cd + run_command(out, "--force"));
    INFO(out << ": " << o.output);
    CHECK(o.exit_code == 2);
    CHECK(o.output == "masnet run: --out '" + out + "': " + message + "\n");
  };
  const std::string cwd_message =
      "an output directory cannot be the working directory or a folder that contains it (masnet "
      "replaces the whole directory); name a new folder, e.g. runs/NAME";
  refused(".", cwd_message);
  refused("./", cwd_message);
  refused("..", cwd_message);
  refused("../work/.", cwd_message);
  refused(s.dir.string(), cwd_message);
  refused("/", "the root folder cannot be an output directory");
  if (const char* home = std::getenv("HOME"); home && fs::path(home).has_relative_path())
    refused(home, "an output directory cannot be the home folder or a folder that contains it");
  CHECK(slurp(s.dir / "work" / "notes.txt") == "the user's own file\n");
  CHECK(fs::exists(s.dir / "work" / "notes.txt"));
}

TEST_CASE("A forced run replaces a run's directory but never a folder of other files (--force)",
          "[scenarios]") {
  Scratch s("force");
  fs::create_directories(s.dir / "mine");
  s.touch("mine/thesis.tex");
  const Outcome o = s.shell(run_command("mine", "--force"));
  CHECK(o.exit_code == 2);
  CHECK(o.output ==
        "masnet run: refusing to replace 'mine': it is not empty and holds no masnet run (no "
        "readable "
        "summary.json), so --force does not apply; choose another --out\n");
  CHECK(slurp(s.dir / "mine" / "thesis.tex") == "the user's own file\n");
  // A different run is replaced with --force only.
  REQUIRE(s.shell(run_command("run")).exit_code == 0);
  const Outcome other = s.shell(run_command("run", "--seed 7"));
  CHECK(other.exit_code == 2);
  CHECK(other.output.find("it holds a different run (scenario 'acoustic_tracking', seed 1)") !=
        std::string::npos);
  CHECK(s.shell(run_command("run", "--seed 7 --force")).exit_code == 0);
  CHECK(nlohmann::json::parse(slurp(s.dir / "run" / "summary.json"))["seed"] == 7);
}

TEST_CASE("A sweep refuses the working directory and a folder of other files, even with --force",
          "[scenarios]") {
  Scratch s("sweep-out");
  std::ofstream(s.dir / "sweep.yaml") << "base: " << kAcoustic << "\nseeds: [1]\n";
  const Outcome dot = s.shell(fmt::format("'{}' sweep sweep.yaml --out . --force", kMasnet));
  CHECK(dot.exit_code == 2);
  CHECK(dot.output.find(
            "masnet sweep: --out '.': an output directory cannot be the working directory") == 0);
  fs::create_directories(s.dir / "data" / "runs");
  s.touch("data/runs/keep.csv");
  const Outcome mine = s.shell(fmt::format("'{}' sweep sweep.yaml --out data --force", kMasnet));
  CHECK(mine.exit_code == 2);
  CHECK(mine.output ==
        "masnet sweep: refusing to write into 'data': it is not empty and holds no sweep results "
        "(results.sqlite); choose another --out\n");
  CHECK(fs::exists(s.dir / "data" / "runs" / "keep.csv"));
}

TEST_CASE("A failed write throws with the file and the system's reason, and never aborts",
          "[scenarios]") {
  // /dev/full accepts the open and fails every write with ENOSPC, as a full disk does.
  REQUIRE(fs::exists("/dev/full"));
  OutputFile out("/dev/full");
  out.write(std::string(100, 'x'));  // buffered: no error yet
  CHECK_THROWS_WITH(out.close(), "cannot write '/dev/full': No space left on device");
  CHECK_THROWS_WITH(write_file("/dev/full", std::string(1 << 17, 'y')),
                    "cannot write '/dev/full': No space left on device");
  {
    // An exception while the file is still open: the destructor closes it without a check.
    OutputFile unclosed("/dev/full");
    unclosed.write("z");
  }
  CHECK_THROWS_WITH(OutputFile("/nonexistent-folder/x.csv"),
                    "cannot write '/nonexistent-folder/x.csv': No such file or directory");
}

TEST_CASE("On a full disk a run publishes a complete directory or nothing", "[scenarios]") {
  if (!can_mount()) {
    WARN("skipped: cannot mount a tmpfs here (needs root and mount namespaces)");
    return;
  }
  Scratch s("full");
  // From too small for the first file to just too small for the figures; the last fits.
  for (const char* size : {"8k", "200k", "700k", "1500k", "8m"}) {
    fs::create_directories(s.dir / "disk");
    const Outcome o =
        s.shell(fmt::format("unshare -m sh -c \"mount -t tmpfs -o size={} tmpfs disk && {} ; echo "
                            "exit=\\$? ; ls -A disk\"",
                            size, run_command("disk/run")));
    INFO("tmpfs of " << size << ":\n" << o.output);
    if (o.output.find("exit=0") != std::string::npos) {
      CHECK(std::string(size) == "8m");
      CHECK(o.output == "exit=0\nrun\n");
      continue;
    }
    CHECK(std::string(size) != "8m");
    CHECK(o.output.find("exit=1") != std::string::npos);
    CHECK(o.output.find("masnet: cannot write the run directory 'disk/run': cannot write '") == 0);
    CHECK(o.output.find("No space left on device") != std::string::npos);
    CHECK(o.output.find("masnet: nothing was written (the partial copy was removed)\n") !=
          std::string::npos);
    // Nothing after "exit=1": the tmpfs holds neither the run nor a partial copy.
    CHECK(o.output.substr(o.output.find("exit=1")) == "exit=1\n");
  }
}

TEST_CASE("A run replacing an older one on a full disk keeps the older one whole", "[scenarios]") {
  if (!can_mount()) {
    WARN("skipped: cannot mount a tmpfs here (needs root and mount namespaces)");
    return;
  }
  Scratch s("full-replace");
  fs::create_directories(s.dir / "disk");
  // The first run fits (3 MB of 4); the second (another seed, --force) does not fit beside it.
  const Outcome o =
      s.shell(fmt::format("unshare -m sh -c \"mount -t tmpfs -o size=4m tmpfs disk && {} && {} ; "
                          "echo exit=\\$? ; ls -A disk; "
                          "grep -q '\\\"seed\\\": 1,' disk/run/summary.json && echo seed-1\"",
                          run_command("disk/run"), run_command("disk/run", "--seed 2 --force")));
  INFO(o.output);
  CHECK(o.output.find("exit=1\nrun\nseed-1\n") != std::string::npos);
}

TEST_CASE("An unwritable destination is refused before simulating, by run and by sweep",
          "[scenarios]") {
  if (!can_mount()) {
    WARN("skipped: cannot make a read-only bind mount here (needs root and mount namespaces)");
    return;
  }
  Scratch s("readonly");
  fs::create_directories(s.dir / "ro");
  std::ofstream(s.dir / "sweep.yaml") << "base: " << kAcoustic << "\nseeds: [1]\n";
  const std::string mount = "mount --bind ro ro && mount -o remount,bind,ro ro";
  const Outcome run =
      s.shell(fmt::format("unshare -m sh -c \"{} && {}\"", mount, run_command("ro/run")));
  CHECK(run.exit_code == 2);
  CHECK(run.output ==
        "masnet run: cannot write in '" + (s.dir / "ro").string() + "': Read-only file system\n");
  const Outcome nested =
      s.shell(fmt::format("unshare -m sh -c \"{} && {}\"", mount, run_command("ro/a/b/run")));
  CHECK(nested.exit_code == 2);
  CHECK(nested.output.find("Read-only file system") != std::string::npos);
  const Outcome sweep = s.shell(fmt::format(
      "unshare -m sh -c \"{} && '{}' sweep sweep.yaml --out ro/sweep\"", mount, kMasnet));
  CHECK(sweep.exit_code == 2);
  CHECK(sweep.output ==
        "masnet sweep: cannot write in '" + (s.dir / "ro").string() + "': Read-only file system\n");
}

TEST_CASE("Directory names are normalised and their forbidden forms recognised", "[scenarios]") {
  const fs::path cwd = fs::current_path();
  CHECK(normalised_directory("a/b/") == cwd / "a" / "b");
  CHECK(normalised_directory("a//b/./") == cwd / "a" / "b");
  CHECK(normalised_directory("a/../c") == cwd / "c");
  CHECK(normalised_directory("/") == fs::path("/"));
  CHECK(forbidden_output_directory("", "--out") == "--out: the directory name is empty");
  CHECK(forbidden_output_directory("runs/x", "--out").empty());
  CHECK_FALSE(forbidden_output_directory(cwd.parent_path().string() + "/", "--out").empty());
  CHECK_FALSE(forbidden_output_directory("//", "--out").empty());
}

TEST_CASE("masnet sweep caps --jobs at its runs and warns above the allowed CPUs", "[scenarios]") {
  Scratch s("jobs");
  std::ofstream(s.dir / "sweep.yaml")
      << "base: " << kAcoustic << "\nseeds: [1, 2]\nset: {duration: 0.2, output.snapshots: []}\n";
  const Outcome o = s.shell(fmt::format("'{}' sweep sweep.yaml --out out --jobs 3000", kMasnet));
  CHECK(o.exit_code == 0);
  CHECK(o.output.find("is more than the ") != std::string::npos);
  CHECK(o.output.find("(capped at the sweep's 2 runs)") != std::string::npos);
  CHECK(o.output.find("with 2 jobs × 1 rank") != std::string::npos);
}

TEST_CASE("A sweep under mpirun on one host notes once how to keep MPI on loopback",
          "[scenarios]") {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0 ||
      std::system(fmt::format("'{}' sweep --help | grep -q -- --no-mpi", kMasnet).c_str()) != 0) {
    WARN("skipped: mpirun is absent (apt-get install openmpi-bin)");
    return;
  }
  Scratch s("mpi-note");
  std::ofstream(s.dir / "sweep.yaml")
      << "base: " << kAcoustic << "\nseeds: [1, 2]\nset: {duration: 0.2, output.snapshots: []}\n";
  const std::string mpirun =
      "ASAN_OPTIONS=detect_leaks=0 mpirun -x ASAN_OPTIONS --oversubscribe --allow-run-as-root";
  const std::string note = "masnet sweep: note: all 2 ranks run on this host";
  const Outcome open =
      s.shell(fmt::format("{} -np 2 '{}' sweep sweep.yaml --out a", mpirun, kMasnet));
  INFO(open.output);
  CHECK(open.exit_code == 0);
  if (open.output.find("see docs/sweeps.md") == std::string::npos) {
    // This host has no interface but loopback (a private network namespace): nothing to note.
    CHECK(open.output.find(note) == std::string::npos);
    return;
  }
  CHECK(masnet::test::count(open.output, note) == 1);
  const Outcome loopback = s.shell(fmt::format(
      "{} --mca btl self,vader --mca oob_tcp_if_include lo -np 2 '{}' sweep sweep.yaml --out b",
      mpirun, kMasnet));
  INFO(loopback.output);
  CHECK(loopback.exit_code == 0);
  CHECK(loopback.output.find(note) == std::string::npos);
}
