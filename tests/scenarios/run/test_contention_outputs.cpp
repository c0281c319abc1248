// What the contended radio levels did, in the run's files: summary.json's keys, the columns of
// nodes.csv and timeseries.csv, the collisions figure and the report's message table — agreeing
// with one another at level csma, and absent at level airtime.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/report/figures.hpp"
#include "scenarios/report/report.hpp"
#include "scenarios/report/run_data.hpp"
#include "scenarios/run/run.hpp"

using namespace masnet;
using namespace masnet::scenarios;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::vector<std::string> kCounts = {"transmissions", "delivered", "collided", "channel_lost",
                                          "dropped",       "retries",   "backoffs"};
const std::vector<std::string> kNodeColumns = {"transmissions", "delivered", "collided",
                                               "channel_lost",  "dropped",   "retries",
                                               "backoffs",      "acks"};

// A short acoustic run at `level`, its files written to a fresh directory.
struct LevelRun {
  fs::path dir;
  json summary;
  explicit LevelRun(const std::string& level) {
    dir = fs::temp_directory_path() / ("masnet-test-contention-" + std::to_string(::getpid())) /
          level;
    fs::remove_all(dir);
    fs::create_directories(dir);
    LoadResult loaded =
        load_scenario(std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml",
                      {"duration=0.3", "output.snapshots=[]", "sensors.nx=20", "sensors.ny=20",
                       "radio.level=" + level});
    INFO((loaded.diagnostics.empty() ? std::string() : loaded.diagnostics[0].text()));
    REQUIRE(loaded.scenario);
    Run run(*loaded.scenario);
    run.execute();
    run.write_files(dir.string());
    std::ifstream in(dir / "summary.json");
    summary = json::parse(in);
  }
  ~LevelRun() {
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::remove(dir.parent_path(), ec);  // once the other level's run is gone too
  }
};

double column_sum(const Table& t, const std::string& name) {
  const std::vector<double>& v = t.column(name);
  return std::accumulate(v.begin(), v.end(), 0.0);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a csma run reports what contention did, the same in every file", "[scenarios]") {
  const LevelRun csma("csma");
  const json& total = csma.summary.at("messages").at("total");
  const json& by_type = csma.summary.at("messages").at("by_type");
  // The scenario is busy enough for contention to show: frames collide, and are delivered.
  REQUIRE(total.at("delivered").get<double>() > 0);
  REQUIRE(total.at("collided").get<double>() > 0);
  CHECK(total.at("backoffs").get<double>() > 0);
  CHECK(total.at("acks").get<double>() > 0);

  // The total is the sum over types.
  for (const std::string& key : kCounts) {
    INFO(key);
    double sum = 0;
    for (const auto& [type, v] : by_type.items())
      sum += v.at(key).get<double>();
    CHECK(sum == total.at(key).get<double>());
  }
  CHECK_FALSE(by_type.begin()->contains("acks"));

  // Latencies: the total mean weighs each type's by its deliveries; the p99 of all types
  // together lies between the types' own.
  double weighted = 0, p99_low = std::numeric_limits<double>::infinity(), p99_high = 0;
  for (const auto& [type, v] : by_type.items()) {
    INFO(type);
    if (v.at("delivered").get<double>() == 0) {
      CHECK(v.at("latency_mean_s").is_null());
      CHECK(v.at("latency_p99_s").is_null());
      continue;
    }
    const double mean_s = v.at("latency_mean_s"), p99_s = v.at("latency_p99_s");
    CHECK(mean_s > 0);
    weighted += mean_s * v.at("delivered").get<double>();
    p99_low = std::min(p99_low, p99_s);
    p99_high = std::max(p99_high, p99_s);
  }
  const double total_mean_s = total.at("latency_mean_s"), total_p99_s = total.at("latency_p99_s");
  CHECK(total_mean_s == Approx(weighted / total.at("delivered").get<double>()).epsilon(1e-12));
  CHECK(total_p99_s >= p99_low);
  CHECK(total_p99_s <= p99_high);

  // nodes.csv: the per-sender columns sum to the totals.
  const Table nodes = Table::read(csma.dir / "nodes.csv");
  REQUIRE(nodes.names().size() >= kNodeColumns.size());
  CHECK(std::equal(kNodeColumns.begin(), kNodeColumns.end(),
                   nodes.names().end() - static_cast<std::ptrdiff_t>(kNodeColumns.size())));
  for (const std::string& key : kNodeColumns) {
    INFO(key);
    CHECK(column_sum(nodes, key) == total.at(key).get<double>());
  }

  // timeseries.csv: collisions never decrease and end at the summary's total.
  const Table ts = Table::read(csma.dir / "timeseries.csv");
  REQUIRE(ts.has("collisions"));
  const std::vector<double>& collisions = ts.column("collisions");
  REQUIRE(collisions.size() >= 2);
  CHECK(std::is_sorted(collisions.begin(), collisions.end()));
  CHECK(collisions.front() < collisions.back());
  CHECK(collisions.back() == total.at("collided").get<double>());

  // The figure and the report, from the files alone.
  const RunData data = load_run_data(csma.dir);
  const std::vector<FigureInfo> figures = write_figures(data, csma.dir / "figures");
  CHECK(std::any_of(figures.begin(), figures.end(),
                    [](const FigureInfo& f) { return f.stem == "collisions"; }));
  CHECK(fs::exists(csma.dir / "figures" / "collisions.svg"));
  const std::string html = slurp(write_report(data, figures, csma.dir / "figures"));
  CHECK(html.find("<th class=\"num\">lost to the channel</th>") != std::string::npos);
  CHECK(html.find("<th class=\"num\">p99 latency (s)</th>") != std::string::npos);
  CHECK(html.find("\"chart-collisions\"") != std::string::npos);
}

TEST_CASE("an airtime run has none of the contention outputs", "[scenarios]") {
  const LevelRun airtime("airtime");
  const json& messages = airtime.summary.at("messages");
  for (const char* key : {"transmissions", "delivered", "collided", "channel_lost", "dropped",
                          "retries", "backoffs", "acks", "latency_mean_s", "latency_p99_s"}) {
    INFO(key);
    CHECK_FALSE(messages.at("total").contains(key));
    for (const auto& [type, v] : messages.at("by_type").items())
      CHECK_FALSE(v.contains(key));
  }
  const Table nodes = Table::read(airtime.dir / "nodes.csv");
  CHECK(nodes.names().back() != "acks");
  for (const std::string& key : kNodeColumns)
    CHECK_FALSE(nodes.has(key));
  CHECK_FALSE(Table::read(airtime.dir / "timeseries.csv").has("collisions"));

  const RunData data = load_run_data(airtime.dir);
  const std::vector<FigureInfo> figures = write_figures(data, airtime.dir / "figures");
  CHECK(std::none_of(figures.begin(), figures.end(),
                     [](const FigureInfo& f) { return f.stem == "collisions"; }));
  const std::string html = slurp(write_report(data, figures, airtime.dir / "figures"));
  CHECK(html.find("lost to the channel") == std::string::npos);
  CHECK(html.find("chart-collisions") == std::string::npos);
}
