// The contention totals in results.sqlite: columns of every sweep, filled for the contended
// radio levels and NULL for the others, and shown by the comparison report when present.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "scenarios/sweep/sweep.hpp"
#include "sweep_helpers.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;
using masnet::test::fresh_dir;
using masnet::test::Row;
using masnet::test::runs_table;
using masnet::test::slurp;
using masnet::test::tiny_sweep_text;
using masnet::test::write_file;

namespace {

const std::vector<std::string> kColumns = {
    "messages_total_transmissions", "messages_total_delivered", "messages_total_collided",
    "messages_total_channel_lost",  "messages_total_dropped",   "messages_total_retries",
    "messages_total_backoffs",      "messages_total_acks",      "messages_total_latency_mean_s",
    "messages_total_latency_p99_s"};

std::vector<Row> sweep(const fs::path& base, const std::string& vary) {
  const fs::path file = write_file(base / "sweep.yaml", tiny_sweep_text(vary));
  SweepLoad loaded = load_sweep(file.string());
  REQUIRE(loaded.sweep);
  SweepOptions options;
  options.out_dir = (base / "out").string();
  const SweepCounts counts = run_sweep_locally(*loaded.sweep, options);
  REQUIRE(counts.failed == 0);
  return runs_table(base / "out");
}

}  // namespace

TEST_CASE("a sweep stores the contention totals, NULL for levels without contention",
          "[scenarios]") {
  const fs::path base = fresh_dir("contention");
  const std::vector<Row> rows = sweep(base, "vary:\n  radio.level: [airtime, csma]\n");
  REQUIRE(rows.size() == 4);
  for (const Row& row : rows) {
    INFO(row.at("label"));
    const bool csma = row.at("p_radio_level") == "csma";
    for (const std::string& column : kColumns) {
      INFO(column);
      REQUIRE(row.count(column) == 1);
      CHECK((row.at(column) == "NULL") == !csma);
    }
    if (csma) {
      CHECK(std::stod(row.at("messages_total_delivered")) > 0);
      CHECK(std::stod(row.at("messages_total_latency_p99_s")) > 0);
      // The per-type figures are ordinary metric columns.
      CHECK(row.at("messages_by_type_discover_collided") != "NULL");
    }
  }
  const std::string html = slurp(base / "out" / "report.html");
  CHECK(html.find("receptions lost to overlap") != std::string::npos);
  CHECK(html.find("delivery latency, p99 (s)") != std::string::npos);
  fs::remove_all(base);
}

TEST_CASE("a sweep without contention has the contention columns, all NULL", "[scenarios]") {
  const fs::path base = fresh_dir("no-contention");
  const std::vector<Row> rows = sweep(base, "vary:\n  radio.level: [ideal, airtime]\n");
  REQUIRE(rows.size() == 4);
  for (const Row& row : rows)
    for (const std::string& column : kColumns) {
      INFO(column);
      REQUIRE(row.count(column) == 1);
      CHECK(row.at(column) == "NULL");
    }
  CHECK(slurp(base / "out" / "results.csv").find("messages_total_collided") != std::string::npos);
  CHECK(slurp(base / "out" / "report.html").find("receptions lost to overlap") ==
        std::string::npos);
  fs::remove_all(base);
}
