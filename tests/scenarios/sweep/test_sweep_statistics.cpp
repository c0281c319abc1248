// Per-configuration statistics of a sweep (docs/sweeps.md, table `statistics`): Student's t
// quantiles against published values, the interval of a mean by hand, and the table written
// by a real sweep against the same numbers recomputed here from its `metrics` table.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include <sqlite3.h>

#include "scenarios/sweep/sweep.hpp"
#include "scenarios/sweep/sweep_statistics.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;

TEST_CASE("Student t quantiles match published values at every degree of freedom", "[scenarios]") {
  // Upper 97.5 % points, to the digits the tables give.
  const std::map<std::size_t, double> published = {
      {1, 12.7062047},  {2, 4.30265273},  {4, 2.77644511},   {9, 2.26215716},   {30, 2.04227246},
      {31, 2.03951345}, {60, 2.00029782}, {100, 1.98397152}, {1000, 1.96233908}};
  for (const auto& [df, t] : published) {
    INFO("df = " << df);
    CHECK(student_t_975(df) == Approx(t).epsilon(1e-8));
  }
  // Above 30 degrees of freedom the quantile is not 1.96 yet: that would shrink intervals.
  CHECK(student_t_975(40) > 2.02);
  CHECK(std::isnan(student_t_975(0)));
}

TEST_CASE("The 95 % confidence interval of a mean, by hand", "[scenarios]") {
  const MeanCi ci = mean_ci95({1, 2, 3, 4, 5});
  CHECK(ci.n == 5);
  CHECK(ci.mean == Approx(3.0));
  CHECK(ci.sd == Approx(std::sqrt(2.5)));
  CHECK(ci.half_width == Approx(2.77644511 * std::sqrt(2.5) / std::sqrt(5.0)));
  CHECK(std::isnan(mean_ci95({4.0}).half_width));
  CHECK(std::isnan(mean_ci95({4.0}).sd));
  CHECK(mean_ci95({4.0}).mean == 4.0);
  CHECK(mean_ci95({}).n == 0);
  CHECK(configuration_label("radio.loss=0.1 seed=3") == "radio.loss=0.1");
  CHECK(configuration_label("seed=3") == "(base)");
}

namespace {

struct Db {
  sqlite3* db = nullptr;
  explicit Db(const fs::path& path) {
    REQUIRE(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
  }
  ~Db() { sqlite3_close(db); }
  // Every row of `sql` as doubles (NULL as NaN) and its first column as text.
  std::vector<std::pair<std::string, std::vector<double>>> rows(const std::string& sql) const {
    sqlite3_stmt* s = nullptr;
    REQUIRE(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) == SQLITE_OK);
    std::vector<std::pair<std::string, std::vector<double>>> out;
    while (sqlite3_step(s) == SQLITE_ROW) {
      std::vector<double> values;
      for (int c = 0; c < sqlite3_column_count(s); ++c)
        values.push_back(sqlite3_column_type(s, c) == SQLITE_NULL ? NAN
                                                                  : sqlite3_column_double(s, c));
      out.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), values);
    }
    sqlite3_finalize(s);
    return out;
  }
};

}  // namespace

TEST_CASE("A sweep's statistics table holds each configuration's mean, sd and interval",
          "[scenarios]") {
  const fs::path base =
      fs::temp_directory_path() / ("masnet-test-statistics-" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  std::ofstream(base / "sweep.yaml")
      << "base: " << MASNET_SOURCE_DIR << "/scenarios/paper/acoustic_tracking.yaml\nseeds: 3\n"
      << "set: {duration: 0.2, sensors.nx: 20, sensors.ny: 20, output.snapshots: [], "
         "output.updates: false}\n"
      << "vary:\n  protocol.kind: [radius_doubling, fixed_radius]\n";
  SweepLoad loaded = load_sweep((base / "sweep.yaml").string());
  REQUIRE(loaded.sweep);
  SweepOptions options;
  options.out_dir = (base / "out").string();
  options.jobs = 2;
  REQUIRE(run_sweep_locally(*loaded.sweep, options).failed == 0);

  const Db db(base / "out" / "results.sqlite");
  // Per run, recomputed here: messages and energy per update.
  const auto runs = db.rows(
      "SELECT r.label, m.value, e.value / u.value FROM runs r JOIN metrics m ON m.run_id = "
      "r.run_id AND m.key = "
      "'messages.total.count' JOIN metrics e ON e.run_id = r.run_id AND e.key = 'energy_j.total' "
      "JOIN metrics u "
      "ON u.run_id = r.run_id AND u.key = 'protocol.updates' ORDER BY r.run_index");
  REQUIRE(runs.size() == 6);
  for (const char* configuration :
       {"protocol.kind=radius_doubling", "protocol.kind=fixed_radius"}) {
    INFO(configuration);
    std::vector<double> messages, energy_per_update;
    for (const auto& [label, values] : runs)
      if (label.rfind(std::string(configuration) + " ", 0) == 0) {
        messages.push_back(values[1]);
        energy_per_update.push_back(values[2]);
      }
    REQUIRE(messages.size() == 3);
    for (const auto& [metric, values] : {std::pair{"messages.total.count", messages},
                                         std::pair{"energy_per_update_j", energy_per_update}}) {
      INFO(metric);
      const auto stats =
          db.rows(std::string("SELECT configuration, n, mean, sd, ci95_low, ci95_high FROM "
                              "statistics WHERE configuration = '") +
                  configuration + "' AND metric = '" + metric + "'");
      REQUIRE(stats.size() == 1);
      const std::vector<double>& s = stats[0].second;
      const double mean = (values[0] + values[1] + values[2]) / 3.0;
      double squares = 0;
      for (double v : values)
        squares += (v - mean) * (v - mean);
      const double sd = std::sqrt(squares / 2.0), half = 4.30265273 * sd / std::sqrt(3.0);
      CHECK(s[1] == 3);
      CHECK(s[2] == Approx(mean));
      CHECK(s[3] == Approx(sd));
      CHECK(s[4] == Approx(mean - half));
      CHECK(s[5] == Approx(mean + half));
    }
  }
  // The question the table exists for, in one query.
  const auto cheapest = db.rows(
      "SELECT configuration, mean, ci95_low, ci95_high FROM statistics WHERE metric = "
      "'energy_per_update_j' "
      "ORDER BY mean LIMIT 1");
  REQUIRE(cheapest.size() == 1);
  CHECK(cheapest[0].second[2] <= cheapest[0].second[1]);
  fs::remove_all(base);
}
