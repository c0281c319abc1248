// Sweeps run in this process: results independent of the number of threads, failed runs,
// resume and --force, keep_runs, and the comparison report.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "headless_chromium.hpp"
#include "scenarios/sweep/sweep.hpp"
#include "scenarios/sweep/sweep_report.hpp"
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
using nlohmann::json;

TEST_CASE(
    "Results do not depend on the number of threads - failed runs are recorded and the others "
    "complete",
    "[scenarios]") {
  const fs::path base = fresh_dir("jobs");
  const fs::path file = write_file(
      base / "sweep.yaml",
      tiny_sweep_text(
          "vary:\n  protocol.kind: [oracle, radius_doubling]\n  radio.loss: [0, 0.2, 2]\n"));
  const SweepDef def = [&] {
    SweepLoad l = load_sweep(file.string());
    REQUIRE(l.sweep);
    return *l.sweep;
  }();
  std::map<int, std::vector<Row>> tables;
  for (int jobs : {1, 2}) {
    SweepOptions options;
    options.out_dir = (base / ("out" + std::to_string(jobs))).string();
    options.jobs = jobs;
    std::size_t executed = 0;
    const SweepCounts counts =
        run_sweep_locally(def, options, [&](const RunResult&) { ++executed; });
    CHECK(counts.total == 12);
    CHECK(executed == 12);
    CHECK(counts.failed == 4);  // radio.loss = 2, two protocols, two seeds
    CHECK(counts.exit_code() == 4);
    tables[jobs] = runs_table(options.out_dir);
  }
  REQUIRE(tables[1].size() == 12);
  CHECK(tables[1] == tables[2]);
  for (const Row& row : tables[1]) {
    INFO(row.at("label"));
    if (row.at("p_radio_loss") == "2") {
      CHECK(row.at("status") == "failed");
      CHECK(row.at("error") == "--set radio.loss=2: radio.loss: must be in [0, 1) (got 2)");
      CHECK(row.at("messages_total_count") == "NULL");
    } else {
      CHECK(row.at("status") == "ok");
      CHECK(row.at("error") == "NULL");
      CHECK(row.at("fingerprint").size() == 16);
      CHECK(row.at("protocol_cell_correctness") != "NULL");
    }
  }
  // Seeds and protocols differ in their fingerprints; the oracle sends nothing.
  CHECK(tables[1][0].at("fingerprint") != tables[1][1].at("fingerprint"));
  CHECK(tables[1][0].at("messages_total_count") == "0");
  CHECK(std::stod(tables[1][6].at("messages_total_count")) > 0);
  // Every metric, including per-type counts, is also in the key/value table.
  CHECK(count_rows(base / "out1",
                   "SELECT count(*) FROM metrics WHERE key = 'messages.by_type.DISCOVER.count'") ==
        8);
  // results.csv: a header and one row per run, the same columns as `runs`.
  const std::string csv = slurp(base / "out1" / "results.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 13);
  CHECK(csv.rfind("run_id,run_index,seed,status,error,label,parameters,fingerprint,finished_at,p_"
                  "protocol_kind,"
                  "p_radio_loss,",
                  0) == 0);
  // Locomotion as one total, not a column per robot.
  const std::string header = csv.substr(0, csv.find('\n'));
  CHECK(header.find(",energy_j_locomotion_total,") != std::string::npos);
  CHECK(header.find("energy_j_locomotion_per_robot") == std::string::npos);
  // Failed runs are in the report with their message.
  const std::string html = slurp(base / "out1" / "report.html");
  CHECK(html.find("12 in the sweep: 8 ok, 4 failed, 0 not run") != std::string::npos);
  CHECK(html.find("must be in [0, 1) (got 2)") != std::string::npos);
  fs::remove_all(base);
}

TEST_CASE("A rerun skips finished runs, retries failed ones, and --force starts afresh",
          "[scenarios]") {
  const fs::path base = fresh_dir("resume");
  const fs::path file =
      write_file(base / "sweep.yaml", tiny_sweep_text("vary:\n  radio.loss: [0, 0.1, 5]\n"));
  SweepLoad loaded = load_sweep(file.string());
  REQUIRE(loaded.sweep);
  SweepOptions options;
  options.out_dir = (base / "out").string();
  options.jobs = 2;
  std::size_t executed = 0;
  auto count = [&](const RunResult&) { ++executed; };

  SweepCounts first = run_sweep_locally(*loaded.sweep, options, count);
  CHECK(executed == 6);
  CHECK(first.failed == 2);
  const std::vector<Row> before = runs_table(options.out_dir);

  executed = 0;
  SweepCounts second = run_sweep_locally(*loaded.sweep, options, count);
  CHECK(executed == 2);  // only the failed runs again
  CHECK(second.skipped == 4);
  CHECK(second.failed == 2);
  CHECK(runs_table(options.out_dir) == before);

  // The same sweep without the impossible value: nothing left to run, and the failed rows are
  // no runs of it any more (kept, without an index).
  const fs::path fixed =
      write_file(base / "fixed.yaml", tiny_sweep_text("vary:\n  radio.loss: [0, 0.1]\n"));
  SweepLoad fixed_sweep = load_sweep(fixed.string());
  REQUIRE(fixed_sweep.sweep);
  executed = 0;
  SweepCounts third = run_sweep_locally(*fixed_sweep.sweep, options, count);
  CHECK(executed == 0);
  CHECK(third.skipped == 4);
  CHECK(third.foreign == 2);
  CHECK(third.exit_code() == 0);
  CHECK(count_rows(options.out_dir, "SELECT count(*) FROM runs WHERE run_index IS NULL") == 2);
  CHECK(count_rows(options.out_dir, "SELECT count(*) FROM sweep") == 3);
  const std::string csv = slurp(base / "out" / "results.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 5);

  options.force = true;
  executed = 0;
  run_sweep_locally(*fixed_sweep.sweep, options, count);
  CHECK(executed == 4);
  CHECK(count_rows(options.out_dir, "SELECT count(*) FROM sweep") == 1);

  // A folder holding something else is refused.
  options.force = false;
  options.out_dir = base.string();  // holds sweep.yaml, no results.sqlite
  CHECK_THROWS_AS(run_sweep_locally(*fixed_sweep.sweep, options), SweepOutputError);
  fs::remove_all(base);
}

TEST_CASE("keep_runs writes a run directory per run", "[scenarios]") {
  const fs::path base = fresh_dir("keep");
  const fs::path file =
      write_file(base / "sweep.yaml",
                 "base: " + kSweepBase + "\nseeds: 1\n" + kTinySet + "output: {keep_runs: true}\n");
  SweepLoad loaded = load_sweep(file.string());
  REQUIRE(loaded.sweep);
  SweepOptions options;
  options.out_dir = (base / "out").string();
  run_sweep_locally(*loaded.sweep, options);
  const std::string id = expand_sweep(*loaded.sweep).at(0).id;
  CHECK(fs::exists(base / "out" / "runs" / id / "summary.json"));
  CHECK(fs::exists(base / "out" / "runs" / id / "sensors.csv"));
  fs::remove_all(base);
}

TEST_CASE(
    "The sweep report is self-contained, with sortable tables, and says when charts are missing",
    "[scenarios]") {
  SweepReportInput in;
  in.title = "demo";
  in.seeds = 3;
  in.total_runs = 7;
  in.axes.push_back({"radio.loss", {"0", "0.1"}, {0.0, 0.1}, true});
  for (std::size_t i = 0; i < 6; ++i) {
    SweepReportRun r;
    r.index = i;
    r.seed = i % 3 + 1;
    r.points = {i / 3};
    r.ok = i != 5;
    r.error = r.ok ? "" : "--set radio.loss=0.1: <boom>";
    r.metrics = {{"messages.total.count", 100.0 + static_cast<double>(i)},
                 {"protocol.cell_correctness", 1.0}};
    in.runs.push_back(r);
  }
  in.chartjs = "/nonexistent/chart.min.js";
  const std::string html = render_sweep_report(in);
  CHECK(html.find("7 in the sweep: 5 ok, 1 failed, 1 not run") != std::string::npos);
  CHECK(html.find("<table class=\"sortable\" id=\"configurations\">") != std::string::npos);
  // Loss 0: 100, 101, 102 -> 101 ± t(2)·1/√3 = 101 ± 2.484.
  CHECK(html.find("101.0 <span class=\"ci\">± 2.484</span>") != std::string::npos);
  CHECK(html.find("&lt;boom&gt;") != std::string::npos);
  CHECK(html.find("id=\"no-charts\"") != std::string::npos);
  CHECK(html.find("<canvas") == std::string::npos);
  CHECK(html.find("src=\"http") == std::string::npos);
  CHECK(html.find("href=\"http") == std::string::npos);

  in.chartjs.clear();
  const std::string with_charts = render_sweep_report(in);
  if (with_charts.find("id=\"no-charts\"") != std::string::npos) {
    WARN("libjs-chart.js is not installed: the sweep report has tables only");
  } else {
    CHECK(with_charts.find("<canvas id=\"chart-0-0\">") != std::string::npos);
    CHECK(with_charts.find("var SWEEP_CHARTS = ") != std::string::npos);
  }
}

TEST_CASE("The sweep report draws its charts in headless Chromium without script errors",
          "[scenarios][chromium]") {
  MASNET_REQUIRE_TOOL(fs::exists(masnet::test::kChromium),
                      "/usr/bin/chromium (apt-get install chromium)");
  // Two factors, one numeric and one categorical: 2 axes × 2 metrics = 4 charts.
  SweepReportInput in;
  in.title = "chromium";
  in.seeds = 2;
  in.total_runs = 8;
  in.axes.push_back({"variant", {"a", "b"}, {0.0, 0.0}, false});
  in.axes.push_back({"radio.loss", {"0", "0.2"}, {0.0, 0.2}, true});
  for (std::size_t i = 0; i < 8; ++i) {
    SweepReportRun r;
    r.index = i;
    r.seed = i % 2 + 1;
    r.points = {i / 4, (i / 2) % 2};
    r.ok = true;
    r.metrics = {{"messages.total.count", 1000.0 + 10.0 * static_cast<double>(i)},
                 {"protocol.cell_correctness", 0.9 + 0.01 * static_cast<double>(i % 3)}};
    in.runs.push_back(r);
  }
  const std::string html = render_sweep_report(in);
  MASNET_REQUIRE_TOOL(html.find("id=\"no-charts\"") == std::string::npos,
                      "Chart.js (apt-get install libjs-chart.js)");
  const fs::path base = fresh_dir("chromium");
  fs::create_directories(base);
  write_file(base / "report.html", html);
  const masnet::test::HeadlessPage opened = masnet::test::open_headless(base / "report.html", base);
  const std::string& dom = opened.dom;
  const std::string& log = opened.log;
  INFO(log.substr(0, 4000));
  REQUIRE(opened.status == 0);
  CHECK(log.find("Uncaught") == std::string::npos);
  CHECK(dom.find("<body data-charts=\"4\">") != std::string::npos);
  fs::remove_all(base);
}
