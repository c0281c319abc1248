// `masnet run --log-level / --log-file` (docs/logging.md): what a debug log shows of one robot,
// that logging never changes a run, and how bad options are refused; `--tiles` (one run cut into
// bands of sensors, docs/decisions/0012-partitioned-runs.md) gives the run in one piece.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "text_files.hpp"

namespace fs = std::filesystem;
using masnet::test::slurp;

namespace {

const std::string kMasnet = std::string(MASNET_BINARY_DIR) + "/scenarios/masnet";

struct Folder {
  fs::path path;
  explicit Folder(const std::string& tag)
      : path(fs::temp_directory_path() /
             fmt::format("masnet-test-logging-{}-{}", tag, ::getpid())) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

struct Result {
  int status = -1;
  std::string out, err;
};

/// A 0.2 s acoustic run without figures into `dir`/run, with `options` appended.
Result masnet_run(const fs::path& dir, const std::string& options) {
  const std::string command = fmt::format(
      "'{}' run '{}/scenarios/paper/acoustic_tracking.yaml' --out '{}' --set duration=0.2 --set "
      "output.snapshots=[] --set output.figures=false --set output.report=false {} > '{}' 2> '{}'",
      kMasnet, MASNET_SOURCE_DIR, (dir / "run").string(), options, (dir / "stdout.txt").string(),
      (dir / "stderr.txt").string());
  Result r;
  const int raw = std::system(command.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(dir / "stdout.txt");
  r.err = slurp(dir / "stderr.txt");
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

std::string fingerprint_of(const fs::path& run_dir) {
  return nlohmann::json::parse(slurp(run_dir / "summary.json"))["fingerprint"].get<std::string>();
}

}  // namespace

TEST_CASE("A debug log follows one robot's update from start through growth to end, in time order",
          "[scenarios]") {
  Folder plain("plain"), logged("debug");
  const Result without = masnet_run(plain.path, "");
  const Result with = masnet_run(
      logged.path, "--log-level debug --log-file '" + (logged.path / "log.txt").string() + "'");
  REQUIRE(without.status == 0);
  REQUIRE(with.status == 0);
  // Logging changes nothing of the run, and nothing of what the terminal shows.
  CHECK(fingerprint_of(logged.path / "run") == fingerprint_of(plain.path / "run"));
  CHECK(with.err.empty());
  CHECK(with.out.find("[t=") == std::string::npos);

  const std::vector<std::string> lines = lines_of(slurp(logged.path / "log.txt"));
  REQUIRE(lines.size() > 100);
  const std::regex line_format(R"(\[t=\s*(\d+\.\d{9}) s\] \[(trace|debug|info|warn|error)\] .+)");
  double last_t = 0.0;
  for (const std::string& line : lines) {
    std::smatch m;
    REQUIRE(std::regex_match(line, m, line_format));
    const double t = std::stod(m[1].str());
    CHECK(t >= last_t);
    last_t = t;
  }
  // Robot 4 (the centre of the 3 x 3 grid): some update starts, grows R at least once, ends.
  const std::regex start(R"(\] \[debug\] robot 4 update (\d+): start at \(.*\), R [0-9.e-]+$)");
  bool followed = false;
  for (std::size_t i = 0; i < lines.size() && !followed; ++i) {
    std::smatch m;
    if (!std::regex_search(lines[i], m, start)) continue;
    const std::string tag = "] [debug] robot 4 update " + m[1].str() + ": ";
    std::size_t growths = 0, j = i + 1;
    for (; j < lines.size(); ++j) {
      if (lines[j].find(tag) == std::string::npos) continue;
      if (std::regex_search(
              lines[j], std::regex(R"(: R [0-9.e-]+ -> [0-9.e-]+ \(farthest sensor [0-9.e-]+\)$)")))
        ++growths;
      if (lines[j].find(tag + "end after ") != std::string::npos) break;
    }
    if (j < lines.size() && growths >= 1) followed = true;
  }
  CHECK(followed);
}

TEST_CASE("Without a log file the log goes to stderr, never to stdout, and level off logs nothing",
          "[scenarios]") {
  Folder to_stderr("stderr"), off("off");
  const Result debug = masnet_run(to_stderr.path, "--log-level debug");
  REQUIRE(debug.status == 0);
  CHECK(debug.err.find("] [debug] robot 0 update 1: start at ") != std::string::npos);
  CHECK(debug.out.find("[t=") == std::string::npos);
  CHECK(debug.out.find("acoustic_tracking: 0.200 s simulated in ") == 0);

  const Result silent =
      masnet_run(off.path, "--log-level off --log-file '" + (off.path / "log.txt").string() + "'");
  REQUIRE(silent.status == 0);
  CHECK(silent.err.empty());
  CHECK(fs::exists(off.path / "log.txt"));
  CHECK(fs::file_size(off.path / "log.txt") == 0);
}

TEST_CASE("The log file is appended to, never truncated", "[scenarios]") {
  Folder folder("append");
  const fs::path log = folder.path / "log.txt";
  { std::ofstream(log) << "kept\n"; }
  REQUIRE(masnet_run(folder.path, "--log-level info --log-file '" + log.string() + "'").status ==
          0);
  const std::string text = slurp(log);
  CHECK(text.rfind("kept\n", 0) == 0);
}

TEST_CASE("A bad log level or an unwritable log file is refused before simulating, exit 2",
          "[scenarios]") {
  Folder folder("bad");
  const Result level = masnet_run(folder.path, "--log-level verbose");
  CHECK(level.status == 2);
  CHECK(level.err.find("--log-level: verbose not in {trace,debug,info,warn,error,off}") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(folder.path / "run"));

  const Result missing = masnet_run(
      folder.path, "--log-file '" + (folder.path / "no/such/folder/log.txt").string() + "'");
  CHECK(missing.status == 2);
  CHECK(missing.err == "masnet run: cannot open the log file '" +
                           (folder.path / "no/such/folder/log.txt").string() +
                           "': No such file or directory\n");
  CHECK_FALSE(fs::exists(folder.path / "run"));

  const Result directory = masnet_run(folder.path, "--log-file '" + folder.path.string() + "'");
  CHECK(directory.status == 2);
  CHECK(directory.err ==
        "masnet run: cannot open the log file '" + folder.path.string() + "': it is a directory\n");
  CHECK_FALSE(fs::exists(folder.path / "run"));

  fs::create_directories(folder.path / "run");
  const Result inside =
      masnet_run(folder.path, "--log-file '" + (folder.path / "run/log.txt").string() + "'");
  CHECK(inside.status == 2);
  CHECK(inside.err == "masnet run: the log file '" + (folder.path / "run/log.txt").string() +
                          "' cannot be inside the run directory '" +
                          (folder.path / "run").string() +
                          "', which is replaced at the end of the run\n");
  CHECK(fs::is_empty(folder.path / "run"));
}

TEST_CASE("masnet run --tiles gives the run in one piece, and refuses what the tiles cannot run",
          "[scenarios]") {
  Folder folder("tiles");
  const Result scheduling = masnet_run(folder.path, "--tiles 2");
  CHECK(scheduling.status == 2);
  CHECK(scheduling.err ==
        "masnet run: --tiles 2: tiles need `tie_order: origin`, the order each tile computes "
        "alone (docs/time-and-ordering.md)\n");
  CHECK_FALSE(fs::exists(folder.path / "run"));

  const Result whole = masnet_run(folder.path, "--set tie_order=origin --quiet");
  REQUIRE(whole.status == 0);
  const std::string expected = fingerprint_of(folder.path / "run");
  const Result cut = masnet_run(folder.path, "--set tie_order=origin --quiet --force --tiles 2");
  REQUIRE(cut.status == 0);
  CHECK(fingerprint_of(folder.path / "run") == expected);
  CHECK(slurp(folder.path / "run/nodes.csv").size() > 0);
}
