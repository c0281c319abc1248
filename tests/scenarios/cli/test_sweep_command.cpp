// `masnet sweep`: the same runs table with --jobs 1, --jobs 2 and MPI ranks, and its exit codes.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "scenarios/cli/sweep_command.hpp"
#include "sweep_helpers.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;
using masnet::test::count_rows;
using masnet::test::fresh_dir;
using masnet::test::kSweepBase;
using masnet::test::kTinySet;
using masnet::test::Row;
using masnet::test::runs_table;
using masnet::test::slurp;
using masnet::test::tiny_sweep_text;
using masnet::test::write_file;

namespace {

const std::string kMasnet = std::string(MASNET_BINARY_DIR) + "/scenarios/masnet";

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

Outcome shell(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  Outcome o;
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  o.output = slurp(log);
  return o;
}

// The masnet binary has the sweep subcommand (cli/command_line.cpp wires it in with
// add_sweep_subcommand). Its help names --jobs; without it, `masnet sweep --help` prints the
// top-level help.
bool masnet_has_sweep() {
  if (!fs::exists(kMasnet)) return false;
  return std::system(("'" + kMasnet + "' sweep --help 2>&1 | grep -q -- --jobs").c_str()) == 0;
}

}  // namespace

TEST_CASE(
    "masnet sweep: same runs table with --jobs 1, --jobs 2 and mpirun -np 2 - and its exit codes",
    "[scenarios]") {
  if (!masnet_has_sweep()) {
    WARN("skipped: '" << kMasnet
                      << " sweep --help' shows no --jobs: the sweep subcommand is not wired into "
                         "the command line yet");
    return;
  }
  const fs::path base = fresh_dir("cli");
  const fs::path file = write_file(
      base / "sweep.yaml", tiny_sweep_text("vary:\n  protocol.kind: [oracle, radius_doubling, "
                                           "gabriel]\n  radio.loss: [0, 0.2, 2]\n"));
  const std::string masnet = "'" + kMasnet + "'";
  const Outcome one = shell(masnet + " sweep '" + file.string() + "' --quiet --jobs 1 --out '" +
                                (base / "j1").string() + "'",
                            base / "j1.log");
  INFO(one.output);
  CHECK(one.exit_code == 6);  // six failed runs: radio.loss = 2
  const Outcome two = shell(masnet + " sweep '" + file.string() + "' --quiet --jobs 2 --out '" +
                                (base / "j2").string() + "'",
                            base / "j2.log");
  CHECK(two.exit_code == 6);
  const std::vector<Row> j1 = runs_table(base / "j1");
  REQUIRE(j1.size() == 18);
  CHECK(runs_table(base / "j2") == j1);

  // Bad sweep file: exit 2, located message, nothing written.
  const fs::path bad =
      write_file(base / "bad.yaml", "base: " + kSweepBase + "\nvary: {radio.loss: 0.1}\n");
  const Outcome refused =
      shell(masnet + " sweep '" + bad.string() + "' --out '" + (base / "bad").string() + "'",
            base / "bad.log");
  CHECK(refused.exit_code == 2);
  CHECK(refused.output.find(bad.string() + ":2:20: vary.radio.loss: expected a list of values") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(base / "bad"));

  // All ok: exit 0, and a rerun runs nothing.
  const fs::path good =
      write_file(base / "good.yaml", tiny_sweep_text("vary: {radio.loss: [0, 0.2]}\n"));
  CHECK(shell(masnet + " sweep '" + good.string() + "' --quiet --out '" + (base / "good").string() +
                  "'",
              base / "good.log")
            .exit_code == 0);
  const Outcome again =
      shell(masnet + " sweep '" + good.string() + "' --out '" + (base / "good").string() + "'",
            base / "again.log");
  CHECK(again.exit_code == 0);
  CHECK(again.output.find("sweep: 4 runs: 0 run now (0 failed), 4 done before") !=
        std::string::npos);

  if (!sweep_has_mpi()) {
    WARN("skipped the MPI case: masnet was built without MPI (libopenmpi-dev, MASNET_WITH_MPI=ON)");
  } else if (std::system("command -v mpirun > /dev/null 2>&1") != 0) {
    WARN("skipped the MPI case: mpirun is absent (apt-get install openmpi-bin)");
  } else {
    const Outcome mpi =
        // Under the asan-ubsan preset, Open MPI's unloaded plugins leave leaks LeakSanitizer
        // cannot attribute (and so cannot suppress): leak checking is off for the ranks only.
        shell(
            "ASAN_OPTIONS=detect_leaks=0 mpirun -x ASAN_OPTIONS --oversubscribe "
            "--allow-run-as-root -np 2 " +
                masnet + " sweep '" + file.string() + "' --quiet --out '" +
                (base / "mpi").string() + "'",
            base / "mpi.log");
    INFO(mpi.output);
    CHECK(mpi.exit_code == 6);
    CHECK(runs_table(base / "mpi") == j1);
    CHECK(count_rows(base / "mpi", "SELECT ranks FROM sweep") == 2);
  }
  fs::remove_all(base);
}
