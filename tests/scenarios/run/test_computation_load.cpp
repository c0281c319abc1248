// The computation-load counts of whole runs of the paper's acoustic scenario (docs/protocols.md,
// "Computation load"): summary.json's totals are the sums of updates.csv's columns, every
// protocol that builds cells counts its clips, and range decay is seen in the counts.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/run/run.hpp"

using namespace masnet;
using namespace masnet::scenarios;
namespace fs = std::filesystem;

namespace {

ScenarioDef acoustic(std::vector<std::string> overrides, double duration_s = 0.5) {
  overrides.push_back("duration=" + std::to_string(duration_s));
  overrides.push_back("output.snapshots=[]");
  LoadResult loaded = load_scenario(
      std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml", overrides, 1);
  INFO((loaded.diagnostics.empty() ? std::string() : loaded.diagnostics[0].text()));
  REQUIRE(loaded.scenario);
  return *loaded.scenario;
}

nlohmann::json geometry_of(const std::vector<std::string>& overrides, double duration_s = 0.5) {
  Run run(acoustic(overrides, duration_s));
  run.execute();
  return run.summary()["protocol"];
}

// Every column of a CSV file of numbers, by name.
std::map<std::string, std::vector<double>> read_columns(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');)
    header.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t c = 0;
    for (std::string cell; std::getline(row, cell, ','); ++c)
      columns[header.at(c)].push_back(cell.empty() ? 0.0 : std::stod(cell));
  }
  return columns;
}

// The sums of two columns of a CSV file, and its number of rows.
struct ColumnSums {
  std::uint64_t rows = 0, clips = 0, tests = 0;
};
ColumnSums sum_columns(const fs::path& path) {
  const auto columns = read_columns(path);
  REQUIRE(columns.count("half_plane_clips") == 1);
  REQUIRE(columns.count("point_in_cell_tests") == 1);
  ColumnSums sums;
  sums.rows = columns.at("half_plane_clips").size();
  for (double clips : columns.at("half_plane_clips"))
    sums.clips += static_cast<std::uint64_t>(clips);
  for (double tests : columns.at("point_in_cell_tests"))
    sums.tests += static_cast<std::uint64_t>(tests);
  return sums;
}

}  // namespace

TEST_CASE("summary.json's computation load is the sum of updates.csv's columns, per protocol",
          "[scenarios]") {
  for (const std::string kind : {"radius_doubling", "oracle", "fixed_radius", "gabriel"}) {
    INFO(kind);
    Run run(acoustic({"protocol.kind=" + kind}));
    run.execute();
    const fs::path dir = fs::temp_directory_path() /
                         ("masnet-test-compload-" + kind + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    run.write_files(dir.string());
    const ColumnSums sums = sum_columns(dir / "updates.csv");
    fs::remove_all(dir);
    const nlohmann::json p = run.summary()["protocol"];
    const nlohmann::json& g = p["geometry"];
    REQUIRE(sums.rows == p["updates"].get<std::uint64_t>());
    REQUIRE(sums.rows > 0);
    CHECK(g["half_plane_clips"].get<std::uint64_t>() == sums.clips);
    CHECK(g["point_in_cell_tests"].get<std::uint64_t>() == sums.tests);
    const double updates = static_cast<double>(sums.rows);
    CHECK(g["clips_per_update"].get<double>() == Approx(static_cast<double>(sums.clips) / updates));
    CHECK(g["point_tests_per_update"].get<double>() ==
          Approx(static_cast<double>(sums.tests) / updates));
    // Nine robots: every cell of every protocol is cut by at least one bisector.
    CHECK(sums.clips >= sums.rows);
    if (kind == "oracle") {
      CHECK(g["sensor_point_tests"] == 0);  // no SENSE
      CHECK(sums.tests >= p["updates"].get<std::uint64_t>());
    } else {
      CHECK(g["sensor_point_tests"].get<std::uint64_t>() > 0);
    }
  }
}

TEST_CASE("on the acoustic scenario range decay costs rounds, and with them clips and point tests",
          "[scenarios]") {
  // Decay shrinks R below what the cell needs, so more updates take a second DISCOVER round and
  // build their cell again (a clip per bisector) with readings to test again: the counts rise
  // with decay on. On 3 seeds of 5 s: 9.28 against 8.08 clips and 6.3 against 1.46 tests per
  // update (scenarios/sweeps/computation_load.yaml); the gap is far wider than between seeds.
  const nlohmann::json on = geometry_of({"protocol.decay.patience=3"}, 1.0);
  const nlohmann::json off = geometry_of({"protocol.decay.patience=0"}, 1.0);
  CHECK(on["rounds_mean"].get<double>() > off["rounds_mean"].get<double>());
  CHECK(on["geometry"]["clips_per_update"].get<double>() >
        off["geometry"]["clips_per_update"].get<double>());
  CHECK(on["geometry"]["point_tests_per_update"].get<double>() >
        2.0 * off["geometry"]["point_tests_per_update"].get<double>());
}

TEST_CASE("summary.json's update statistics do not depend on updates.csv and are its means",
          "[scenarios]") {
  // A run without updates.csv keeps running sums instead of every update: the same summary.
  Run with_rows(acoustic({"output.updates=true"}, 1.0));
  with_rows.execute();
  Run without_rows(acoustic({"output.updates=false"}, 1.0));
  without_rows.execute();
  const nlohmann::json p = with_rows.summary()["protocol"];
  CHECK(p.dump() == without_rows.summary()["protocol"].dump());
  CHECK(with_rows.summary()["energy_j"].dump() == without_rows.summary()["energy_j"].dump());

  const fs::path dir =
      fs::temp_directory_path() / ("masnet-test-update-statistics-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  with_rows.write_files(dir.string());
  const auto columns = read_columns(dir / "updates.csv");
  fs::remove_all(dir);
  const std::vector<double>& rounds = columns.at("rounds");
  const double updates = static_cast<double>(rounds.size());
  REQUIRE(rounds.size() == p["updates"].get<std::size_t>());
  REQUIRE(updates > 20);
  const auto mean = [&](const std::string& name) {
    double sum = 0;
    for (double v : columns.at(name))
      sum += v;
    return sum / updates;
  };
  const auto count = [&](const std::string& name) {
    return static_cast<std::uint64_t>(mean(name) * updates + 0.5);
  };
  CHECK(p["rounds_mean"].get<double>() == Approx(mean("rounds")));
  CHECK(p["radius_mean"].get<double>() == Approx(mean("radius")));
  CHECK(p["latency_mean_s"].get<double>() == Approx(mean("latency_s")));
  CHECK(p["latency_max_s"].get<double>() ==
        Approx(*std::max_element(columns.at("latency_s").begin(), columns.at("latency_s").end())));
  CHECK(p["rounds_max"].get<double>() == *std::max_element(rounds.begin(), rounds.end()));
  CHECK(p["truncated"].get<std::uint64_t>() == count("truncated"));
  CHECK(p["delayed_updates"].get<std::uint64_t>() == count("delayed"));
  CHECK(p["cell_correctness"].get<double>() == Approx(mean("correct")));
  CHECK(p["messages_per_update"]["DISCOVER"].get<double>() == Approx(mean("DISCOVER_count")));
}
