// Parameter sweeps: expansion of a sweep file (lists, ranges, zip, variants, seeds), stable run
// ids, positioned errors, results independent of --jobs and of MPI ranks, resume, failed runs,
// exit codes, and the comparison report.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <sqlite3.h>

#include "headless_chromium.hpp"
#include "scenarios/sweep.hpp"
#include "scenarios/sweep_command.hpp"
#include "scenarios/sweep_report.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kSource = MASNET_SOURCE_DIR;
const std::string kMasnet = std::string(MASNET_BINARY_DIR) + "/scenarios/masnet";
const std::string kBase = kSource + "/scenarios/paper/acoustic_tracking.yaml";
// A sweep file "in" scenarios/sweeps/, so that `base: ../paper/...` resolves as in the examples.
const std::string kInline = kSource + "/scenarios/sweeps/inline.yaml";

// A tiny acoustic run: 0.2 s, 20 × 20 sensors, no snapshots (≈ 0.05 s each).
const char* kTinySet =
    "set: {duration: 0.2, sensors.nx: 20, sensors.ny: 20, output.snapshots: [], output.updates: "
    "false}\n";

SweepDef parse(const std::string& text) {
  SweepLoad loaded = load_sweep_text(text, kInline);
  std::string messages;
  for (const auto& d : loaded.diagnostics)
    messages += d.text() + "\n";
  INFO(messages);
  REQUIRE(loaded.sweep);
  return *loaded.sweep;
}

std::vector<std::string> errors(const std::string& text) {
  SweepLoad loaded = load_sweep_text(text, kInline);
  CHECK_FALSE(loaded.sweep);
  std::vector<std::string> lines;
  for (const auto& d : loaded.diagnostics)
    lines.push_back(d.text());
  return lines;
}

std::vector<json> values_of(const SweepDef& def, std::size_t axis) {
  std::vector<json> v;
  for (const auto& p : def.axes.at(axis).points)
    v.push_back(p.overrides.at(0).value);
  return v;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("masnet-test-sweep-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

fs::path write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

using masnet::test::slurp;

using Row = std::map<std::string, std::string>;

// The `runs` table by run_index, every column as text, wall-clock columns left out.
std::vector<Row> runs_table(const fs::path& dir) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2((dir / "results.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr) ==
          SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, "SELECT * FROM runs ORDER BY run_index", -1, &stmt, nullptr) ==
          SQLITE_OK);
  std::vector<Row> rows;
  while (sqlite3_step(stmt) == SQLITE_ROW) {
    Row row;
    for (int c = 0; c < sqlite3_column_count(stmt); ++c) {
      const std::string name = sqlite3_column_name(stmt, c);
      if (name == "wall_time_s" || name == "finished_at") continue;
      const unsigned char* text = sqlite3_column_text(stmt, c);
      row[name] = text ? reinterpret_cast<const char*>(text) : "NULL";
    }
    rows.push_back(std::move(row));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return rows;
}

std::size_t count_rows(const fs::path& dir, const std::string& sql) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2((dir / "results.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr) ==
          SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) == SQLITE_OK);
  REQUIRE(sqlite3_step(stmt) == SQLITE_ROW);
  const auto n = static_cast<std::size_t>(sqlite3_column_int64(stmt, 0));
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return n;
}

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

// The masnet binary has the sweep subcommand (main.cpp wires it in with add_sweep_subcommand).
// Its help names --jobs; without it, `masnet sweep --help` prints the top-level help.
bool masnet_has_sweep() {
  if (!fs::exists(kMasnet)) return false;
  return std::system(("'" + kMasnet + "' sweep --help 2>&1 | grep -q -- --jobs").c_str()) == 0;
}

std::string tiny_sweep_text(const std::string& extra) {
  return "base: " + kBase + "\nseeds: 2\n" + kTinySet + extra;
}

}  // namespace

TEST_CASE("A sweep expands lists as a cartesian product with the seeds varying fastest",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "seeds: 3\n"
      "vary:\n"
      "  protocol.kind: [oracle, gabriel]\n"
      "  radio.loss: [0, 0.25]\n");
  CHECK(def.base_path == fs::path(kBase).lexically_normal().string());
  CHECK(def.seeds == std::vector<std::uint64_t>{1, 2, 3});
  CHECK(def.parameters == std::vector<std::string>{"protocol.kind", "radio.loss"});
  const std::vector<RunSpec> runs = expand_sweep(def);
  REQUIRE(runs.size() == 12);
  CHECK(runs[0].overrides == std::vector<std::string>{"protocol.kind=\"oracle\"", "radio.loss=0"});
  CHECK(runs[0].seed == 1);
  CHECK(runs[2].seed == 3);
  CHECK(runs[3].overrides ==
        std::vector<std::string>{"protocol.kind=\"oracle\"", "radio.loss=0.25"});
  CHECK(runs[6].parameters == json{{"protocol.kind", "gabriel"}, {"radio.loss", 0}});
  CHECK(runs[11].label == "protocol.kind=gabriel radio.loss=0.25 seed=3");
  for (std::size_t i = 0; i < runs.size(); ++i)
    CHECK(runs[i].index == i);
}

TEST_CASE("Ranges are inclusive and give round decimal values, integers stay integers",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "vary:\n"
      "  radio.loss: {from: 0.0, to: 0.5, step: 0.1}\n"
      "  protocol.decay.patience: {from: 1, to: 7, step: 3}\n"
      "  protocol.decay.step: {from: 0.3, to: 0.1, step: -0.1}\n"
      "  radio.latency: {from: 1e-4, to: 3e-4, step: 1e-4}\n");
  CHECK(values_of(def, 0) == std::vector<json>{0.0, 0.1, 0.2, 0.3, 0.4, 0.5});
  CHECK(values_of(def, 0)[3].dump() == "0.3");  // not 0.30000000000000004
  CHECK(values_of(def, 1) == std::vector<json>{1, 4, 7});
  CHECK(values_of(def, 1)[0].is_number_integer());
  CHECK(values_of(def, 2) == std::vector<json>{0.3, 0.2, 0.1});
  CHECK(values_of(def, 3) == std::vector<json>{0.0001, 0.0002, 0.0003});
  CHECK(expand_sweep(def).size() == 6 * 3 * 3 * 3);
  // Directly: many small steps still reach `to` exactly once.
  const auto fine = sweep_range(0.0, 1.0, 0.01, 2, false);
  REQUIRE(fine.size() == 101);
  CHECK(fine.back() == json(1.0));
  CHECK(fine[7] == json(0.07));
  CHECK(sweep_range(0, 1, 0, 0, true).empty());
  CHECK(sweep_range(1, 0, 0.5, 1, false).empty());
}

TEST_CASE("Zipped keys vary together - variants are named override sets - seeds may be listed",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "seeds: [7, 3]\n"
      "set: {duration: 2.0}\n"
      "variants:\n"
      "  - {name: seed_rule, protocol.kind: radius_doubling, protocol.criterion: sensors}\n"
      "  - {name: cortes, protocol.kind: radius_doubling, protocol.criterion: vertices, "
      "protocol.growth: double}\n"
      "vary:\n"
      "  protocol.decay.patience: [1, 3, 5]\n"
      "  radio.loss: [0, 0.1]\n"
      "  protocol.decay.step: [0.01, 0.02, 0.04]\n"
      "zip: [[protocol.decay.patience, protocol.decay.step]]\n");
  REQUIRE(def.axes.size() == 3);  // variants, the zip group, radio.loss
  CHECK(def.axes[0].name == "variant");
  CHECK(def.axes[1].keys ==
        std::vector<std::string>{"protocol.decay.patience", "protocol.decay.step"});
  CHECK(def.axes[1].points[2].label == "(5, 0.04)");
  CHECK(def.parameters == std::vector<std::string>{"variant", "protocol.kind", "protocol.criterion",
                                                   "protocol.growth", "protocol.decay.patience",
                                                   "protocol.decay.step", "radio.loss"});
  const std::vector<RunSpec> runs = expand_sweep(def);
  REQUIRE(runs.size() == 2 * 3 * 2 * 2);
  CHECK(runs[0].seed == 7);
  CHECK(runs[1].seed == 3);
  // set first, then the variant, then the varied keys.
  CHECK(runs[0].overrides ==
        std::vector<std::string>{"duration=2.0", "protocol.kind=\"radius_doubling\"",
                                 "protocol.criterion=\"sensors\"", "protocol.decay.patience=1",
                                 "protocol.decay.step=0.01", "radio.loss=0"});
  const RunSpec& last = runs.back();
  CHECK(last.parameters["variant"] == "cortes");
  CHECK(last.parameters["protocol.growth"] == "double");
  CHECK(last.parameters["protocol.decay.patience"] == 5);
  CHECK(last.parameters["protocol.decay.step"] == 0.04);
  CHECK_FALSE(runs[0].parameters.contains("protocol.growth"));
}

TEST_CASE("Run ids are stable: the same base, overrides and seed give the same id", "[scenarios]") {
  const std::string text =
      "base: ../paper/acoustic_tracking.yaml\nseeds: 2\nvary: {radio.loss: [0, 0.1]}\n";
  const std::vector<RunSpec> a = expand_sweep(parse(text)), b = expand_sweep(parse(text));
  REQUIRE(a.size() == 4);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].id == b[i].id);
    CHECK(a[i].id.size() == 16);
    ids.insert(a[i].id);
  }
  CHECK(ids.size() == 4);
  // The same run in another sweep (another order, a comment, other values beside it) keeps its id.
  const std::vector<RunSpec> c = expand_sweep(
      parse("# the same runs, and more\nbase: ../paper/acoustic_tracking.yaml\nseeds: [2, 1, 5]\n"
            "vary: {radio.loss: [0.1, 0.3, 0]}\n"));
  std::set<std::string> c_ids;
  for (const auto& r : c)
    c_ids.insert(r.id);
  for (const auto& id : ids)
    CHECK(c_ids.count(id));
  // Direct: order of overrides of distinct keys does not matter, values and seed do.
  const std::string k = "0123456789abcdef";
  const SweepOverride loss{"radio.loss", 0.1}, kind{"protocol.kind", "oracle"};
  CHECK(sweep_run_id(k, {loss, kind}, 1) == sweep_run_id(k, {kind, loss}, 1));
  CHECK(sweep_run_id(k, {loss, kind}, 1) != sweep_run_id(k, {loss, kind}, 2));
  CHECK(sweep_run_id(k, {loss}, 1) != sweep_run_id(k, {SweepOverride{"radio.loss", 0.2}}, 1));
  CHECK(sweep_run_id(k, {loss}, 1) != sweep_run_id("fedcba9876543210", {loss}, 1));
}

TEST_CASE("A bad sweep file gets file:line:col errors", "[scenarios]") {
  const std::string f = kInline;
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\n"
               "vary:\n"
               "  protocol.decay.patience: [1, 3, 5]\n"
               "  protocol.decay.step: [0.01, 0.02]\n"
               "zip: [[protocol.decay.patience, protocol.decay.step]]\n") ==
        std::vector<std::string>{
            f + ":5:7: zip[0]: keys zipped together need lists of the same length, but "
                "'protocol.decay.patience' has 3 values and 'protocol.decay.step' has 2"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nseed: 3\n") ==
        std::vector<std::string>{
            f + ":2:1: unknown key 'seed' in a sweep file (allowed: base, seeds, set, "
                "variants, vary, zip, output, name, description) (did you mean 'seeds'?)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nseeds: 0\n") ==
        std::vector<std::string>{
            f + ":2:8: seeds: expected a count between 1 and 1000000 (seeds 1..N) or a "
                "list of seeds, got '0'"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  radio.loss: {from: 0, to: 1, step: "
               "-0.1}\n") ==
        std::vector<std::string>{
            f + ":3:38: vary.radio.loss.step: must be non-zero and go from 'from' towards "
                "'to' (from 0 to 1 by -0.1)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  radio.loss: 0.1\n") ==
        std::vector<std::string>{
            f + ":3:15: vary.radio.loss: expected a list of values, e.g. [0, 0.1, 0.2], "
                "or a range {from: 0, to: 0.5, step: 0.1}"});
  CHECK(errors("base: ../paper/missing.yaml\n") ==
        std::vector<std::string>{f + ":1:7: base: cannot read the scenario '" +
                                 (fs::path(kSource) / "scenarios/paper/missing.yaml").string() +
                                 "' (No such file or directory)"});
  // A key the scenario does not have is the sweep file's error, located in the sweep file.
  CHECK(
      errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  protocol.knd: [oracle, gabriel]\n") ==
      std::vector<std::string>{
          f + ":3:3: 'protocol.knd' is not a key of the base scenario: unknown key "
              "'knd' in 'protocol' (did you mean 'kind'?)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nset: {duration: 1}\nvary: {duration: [1, "
               "2]}\n") ==
        std::vector<std::string>{
            f + ":3:8: vary: 'duration' is also fixed under 'set'; give it in one place"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary: {seed: [1, 2]}\n") ==
        std::vector<std::string>{
            f + ":2:8: 'seed' cannot be overridden: every run gets its seed from 'seeds' "
                "(a count or a list)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary: {radio.loss: [0.1, 0.2, 0.1]}\n") ==
        std::vector<std::string>{f + ":2:31: vary.radio.loss: the value 0.1 is listed twice"});
  CHECK(
      errors(
          "base: ../paper/acoustic_tracking.yaml\nvariants:\n  - {name: a, protocol.kind: oracle}\n"
          "  - {name: b, protocol.kind: oracle}\n") ==
      std::vector<std::string>{
          f + ":4:5: variants[1]: sets the same keys to the same values as variants[0] "
              "(the runs would be identical)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\noutput: {dir: x, keep: true}\n") ==
        std::vector<std::string>{f + ":2:18: unknown key 'keep' in 'output'"});
  CHECK(errors("base: [oops\n").at(0).rfind(f + ":", 0) == 0);
}

TEST_CASE("Summary metrics flatten to dotted keys and SQL column names", "[scenarios]") {
  const json summary = {
      {"seed", 3},
      {"wall_time_s", 0.5},
      {"fingerprint", "abc"},
      {"messages", {{"total", {{"count", 10}}}, {"by_type", {{"DISCOVER", {{"count", 4}}}}}}},
      {"tracking", {{"robots_per_target", {5, 4}}}},
      {"scenario", {{"robots", 9}, {"resolved", {{"duration", 5.0}}}}},
      {"flag", true}};
  const auto flat = flatten_metrics(summary);
  const std::map<std::string, double> m(flat.begin(), flat.end());
  CHECK(m == std::map<std::string, double>{{"flag", 1.0},
                                           {"messages.by_type.DISCOVER.count", 4.0},
                                           {"messages.total.count", 10.0},
                                           {"scenario.robots", 9.0},
                                           {"tracking.robots_per_target.0", 5.0},
                                           {"tracking.robots_per_target.1", 4.0},
                                           {"wall_time_s", 0.5}});
  CHECK(sanitize_column("messages.by_type.DISCOVER.count") == "messages_by_type_discover_count");
  CHECK(sanitize_column("p_protocol.kind") == "p_protocol_kind");
}

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
                 "base: " + kBase + "\nseeds: 1\n" + kTinySet + "output: {keep_runs: true}\n");
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

TEST_CASE(
    "masnet sweep: same runs table with --jobs 1, --jobs 2 and mpirun -np 2 - and its exit codes",
    "[scenarios]") {
  if (!masnet_has_sweep()) {
    WARN("skipped: '"
         << kMasnet
         << " sweep --help' shows no --jobs: the sweep subcommand is not wired into main.cpp yet");
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
      write_file(base / "bad.yaml", "base: " + kBase + "\nvary: {radio.loss: 0.1}\n");
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
