// The figures and report section of runs with faults or batteries (docs/outputs.md): drawn when
// the run directory has the lifetime columns and sections, absent otherwise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scenarios/report/figures.hpp"
#include "scenarios/report/report.hpp"
#include "short_run.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace masnet::scenarios;

namespace {

using masnet::test::ShortRun;
using masnet::test::slurp;

const ShortRun& short_run() {
  static const ShortRun run("fault-report");
  return run;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    out.push_back(line);
  return out;
}

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');)
    out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The short fault-free run's directory, given what a run with a fault writes: robot 0 down at
// 0.5 s, the lifetime columns, the twin's columns (its cost 10 % below), and the sections.
fs::path faulty_copy(const ShortRun& run) {
  const fs::path dir = run.base / "faulty";
  fs::remove_all(dir);
  fs::copy(run.dir, dir, fs::copy_options::recursive);
  fs::remove_all(dir / "figures");

  std::vector<std::string> ts = lines_of(slurp(dir / "timeseries.csv"));
  const std::vector<std::string> names = cells_of(ts[0]);
  const auto at = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  ts[0] +=
      ",alive_sensors,alive_robots,locomotion_j,cell_correctness_recent,coverage_cost_twin,"
      "tracking_error_mean_twin,cell_correctness_recent_twin";
  for (std::size_t k = 1; k < ts.size(); ++k) {
    const std::vector<std::string> c = cells_of(ts[k]);
    const double t = std::stod(c[at("t_s")]);
    ts[k] += fmt::format(",1600,{},{},{},{},{},1", t < 0.5 ? 9 : 8, 100 * t, t < 0.5 ? 1.0 : 0.8,
                         0.9 * std::stod(c[at("coverage_cost")]),
                         std::stod(c[at("tracking_error_mean")]));
  }
  std::string text;
  for (const std::string& l : ts)
    text += l + "\n";
  write(dir / "timeseries.csv", text);

  std::vector<std::string> nodes = lines_of(slurp(dir / "nodes.csv"));
  nodes[0] += ",locomotion_j,distance_m";
  text = nodes[0] + "\n";
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    std::vector<std::string> c = cells_of(nodes[k]);
    const bool robot = c[1] == "robot";
    if (k == 1 || k == 20) {  // robot 0 and a sensor down
      c[5] = "0";
      c[6] = k == 1 ? "0.5" : "0.8";
    }
    std::string row;
    for (std::size_t i = 0; i < c.size(); ++i)
      row += (i ? "," : "") + c[i];
    text += row + (robot ? fmt::format(",{},{}", 10 * k, 2 * k) : std::string(",,")) + "\n";
  }
  write(dir / "nodes.csv", text);

  json summary = json::parse(slurp(dir / "summary.json"));
  summary["lifetime"] = {{"first_sensor_death_s", 0.8},
                         {"sensors_dead_10pct_s", nullptr},
                         {"sensors_dead_50pct_s", nullptr},
                         {"first_robot_death_s", 0.5},
                         {"deaths", {{"battery", 1}, {"fault", 1}, {"sensors", 1}, {"robots", 1}}},
                         {"restarts", 0},
                         {"sensors_alive_final", 1599},
                         {"robots_alive_final", 8}};
  summary["recovery"] = json::array({{{"index", 0},
                                      {"kind", "kill"},
                                      {"at_s", 0.5},
                                      {"until_s", nullptr},
                                      {"struck", true},
                                      {"coverage_recovery_s", nullptr},
                                      {"correctness_recovery_s", 0.25}}});
  summary["twin"] = {{"fingerprint", "0123456789abcdef"},
                     {"coverage_final_cost", 1.5},
                     {"tracking_mean_error", 0.02},
                     {"energy_total_j", 3.25},
                     {"updates", 77}};
  write(dir / "summary.json", summary.dump(2));
  return dir;
}

const std::vector<std::string> kFaultFigures{"energy_map", "alive_nodes", "twin_comparison"};

}  // namespace

TEST_CASE(
    "A run with faults has an energy map, nodes up, the twin beside it and a lifetime section",
    "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  const fs::path dir = faulty_copy(run);
  const fs::path report = render_run_directory(dir);
  for (const std::string& stem : kFaultFigures) {
    INFO(stem);
    CHECK(slurp(dir / "figures" / (stem + ".svg")).size() > 5000);
    CHECK(fs::file_size(dir / "figures" / (stem + ".png")) > 5000);
  }
  const std::string html = slurp(report);
  const std::size_t section = html.find("<section id=\"lifetime\">");
  REQUIRE(section != std::string::npos);
  const std::size_t end = html.find("</section>", section);
  const std::string lifetime = html.substr(section, end - section);
  CHECK(html.find("<a href=\"#lifetime\">") != std::string::npos);
  CHECK(lifetime.find("id=\"lifetime-table\"") != std::string::npos);
  CHECK(lifetime.find("<tr><th>first robot down (s)</th><td class=\"num\">0.5</td></tr>") !=
        std::string::npos);
  CHECK(lifetime.find("<tr><th>10 % of the sensors down (s)</th><td class=\"num\">never</td>") !=
        std::string::npos);
  CHECK(lifetime.find("<tr><th>nodes down: battery, fault</th><td class=\"num\">1, 1</td>") !=
        std::string::npos);
  // The recovery row: coverage never back within 5 %, correctness after 0.25 s.
  CHECK(lifetime.find("<tr><td>0</td><td>kill</td><td class=\"num\">0.5</td><td "
                      "class=\"num\">never</td><td class=\"num\">never</td><td "
                      "class=\"num\">0.25</td></tr>") != std::string::npos);
  CHECK(lifetime.find("id=\"twin-table\"") != std::string::npos);
  CHECK(lifetime.find("<code>0123456789abcdef</code>") != std::string::npos);
  // The three figures sit in this section, not again under Figures.
  for (const std::string& stem : kFaultFigures) {
    CHECK(lifetime.find("<figure id=\"figure-" + stem + "\">") != std::string::npos);
    CHECK(masnet::test::count(html, "<figure id=\"figure-" + stem + "\">") == 1);
  }
  if (find_chartjs({})) {
    CHECK(html.find("<canvas id=\"chart-alive\">") != std::string::npos);
    CHECK(html.find("<canvas id=\"chart-twin\">") != std::string::npos);
  }
}

TEST_CASE(
    "A run without faults or batteries has no lifetime section and its energy map under Figures",
    "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  const std::string html = slurp(run.dir / "report.html");
  CHECK(html.find("id=\"lifetime\"") == std::string::npos);
  CHECK(html.find("chart-alive") == std::string::npos);
  for (const char* stem : {"alive_nodes", "twin_comparison"})
    CHECK_FALSE(fs::exists(run.dir / "figures" / (std::string(stem) + ".png")));
  // The energy map is drawn for every run with nodes.csv.
  CHECK(fs::file_size(run.dir / "figures" / "energy_map.png") > 5000);
  const std::size_t section = html.find("<section id=\"figures\">");
  REQUIRE(section != std::string::npos);
  CHECK(html.find("<figure id=\"figure-energy_map\">", section) != std::string::npos);
  CHECK(masnet::test::count(html, "<figure id=\"figure-energy_map\">") == 1);
  // Energy by phase is in every run's summary; lifetime only in runs with faults or batteries.
  const json summary = json::parse(slurp(run.dir / "summary.json"));
  CHECK(summary["energy_j"].contains("by_phase"));
  CHECK_FALSE(summary.contains("lifetime"));
}
