#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "scenarios/report/figures.hpp"
#include "scenarios/report/plot/plot.hpp"
#include "scenarios/report/report.hpp"
#include "short_run.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace masnet::scenarios;

namespace {

using masnet::test::count;
using masnet::test::slurp;

std::string last_line(const std::string& text) {
  std::string s = text;
  while (!s.empty() && s.back() == '\n')
    s.pop_back();
  const std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

using masnet::test::ShortRun;

const ShortRun& short_run() {
  static const ShortRun run("figures");
  return run;
}

struct PngSize {
  std::uint32_t width = 0, height = 0;
};

// Width and height from a PNG's IHDR chunk; zero when the signature is wrong.
PngSize png_size(const std::string& bytes) {
  static const std::string kSignature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 24 || bytes.compare(0, 8, kSignature) != 0 ||
      bytes.compare(12, 4, "IHDR") != 0)
    return {};
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k)
      v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

// An SVG document as Cairo writes it: XML declaration, one <svg> root, balanced groups.
void check_svg(const fs::path& path) {
  INFO(path.string());
  const std::string svg = slurp(path);
  CHECK(svg.size() > 5000);
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(count(svg, "<svg ") == 1);
  CHECK(last_line(svg) == "</svg>");
  CHECK(count(svg, "<g ") + count(svg, "<g>") == count(svg, "</g>"));
  CHECK(count(svg, "<path ") > 10);
}

void check_png(const fs::path& path) {
  INFO(path.string());
  const std::string png = slurp(path);
  const PngSize size = png_size(png);
  CHECK(png.size() > 5000);
  CHECK(size.width >= 400);
  CHECK(size.height >= 300);
}

}  // namespace

TEST_CASE(
    "A short run prints its report's path last and writes every figure as PNG and SVG and PDF",
    "[scenarios]") {
  const ShortRun& run = short_run();
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(last_line(run.output) == "report: " + (fs::absolute(run.dir) / "report.html").string());
  CHECK(fs::exists(run.dir / "sensors.csv"));
  const fs::path figures = run.dir / "figures";
  for (const char* stem :
       {"snapshot_t0.5", "snapshot_t1.0", "trajectories", "coverage_cost", "tracking", "radius",
        "messages", "energy", "correctness", "energy_map"}) {
    check_png(figures / (std::string(stem) + ".png"));
    check_svg(figures / (std::string(stem) + ".svg"));
    CHECK(slurp(figures / (std::string(stem) + ".pdf")).rfind("%PDF-", 0) == 0);
  }
  // Figures of other kinds of run are not drawn for an acoustic one.
  CHECK_FALSE(fs::exists(figures / "pollution.png"));
  CHECK_FALSE(fs::exists(figures / "field_t0.5.png"));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(figures))
    ++files;
  CHECK(files == 30);
}

TEST_CASE("Each snapshot SVG holds one cell element per robot, as the robot computed it",
          "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  const json summary = json::parse(slurp(run.dir / "summary.json"));
  const json snapshots = json::parse(slurp(run.dir / "snapshots.json"));
  const std::size_t robots = summary["scenario"]["robots"].get<std::size_t>();
  REQUIRE(robots == 9);
  REQUIRE(snapshots.size() == 2);
  for (const json& snap : snapshots) {
    const std::string stem = "snapshot_t" + snapshot_time_label(snap["t"].get<double>());
    INFO(stem);
    const std::string svg = slurp(run.dir / "figures" / (stem + ".svg"));
    std::size_t with_cell = 0;
    for (const json& r : snap["robots"])
      with_cell += r["cell"].empty() ? 0 : 1;
    CHECK(with_cell == robots);  // by t = 0.5 s every robot has computed its cell
    CHECK(count(svg, "class=\"cell\"") == with_cell);
    CHECK(count(svg, "class=\"oracle-cell\"") == robots);
    for (std::size_t i = 0; i < robots; ++i)
      CHECK(count(svg, fmt::format("id=\"cell-{}\"", i)) == 1);
  }
}

TEST_CASE("masnet render redraws byte-identical figures and report from the run's files",
          "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  std::map<std::string, std::string> before;
  for (const auto& entry : fs::directory_iterator(run.dir / "figures"))
    before[entry.path().filename().string()] = slurp(entry.path());
  const std::string report_before = slurp(run.dir / "report.html");
  REQUIRE(before.size() == 30);

  const fs::path out = run.base / "render.txt";
  const std::string command = fmt::format("'{}/scenarios/masnet' render '{}' > '{}' 2>&1",
                                          MASNET_BINARY_DIR, run.dir.string(), out.string());
  REQUIRE(std::system(command.c_str()) == 0);
  CHECK(last_line(slurp(out)) == "report: " + (fs::absolute(run.dir) / "report.html").string());
  std::size_t after = 0;
  for (const auto& entry : fs::directory_iterator(run.dir / "figures")) {
    const std::string name = entry.path().filename().string();
    INFO(name);
    ++after;
    REQUIRE(before.count(name) == 1);
    CHECK(slurp(entry.path()) == before[name]);
  }
  CHECK(after == before.size());
  CHECK(slurp(run.dir / "report.html") == report_before);
}

TEST_CASE("masnet render refuses a directory that holds no run", "[scenarios]") {
  const fs::path empty =
      fs::temp_directory_path() / fmt::format("masnet-test-empty-{}", ::getpid());
  fs::create_directories(empty);
  const std::string command = fmt::format("'{}/scenarios/masnet' render '{}' > /dev/null 2>&1",
                                          MASNET_BINARY_DIR, empty.string());
  const int status = std::system(command.c_str());
  fs::remove_all(empty);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 2);
}

namespace {

// A diffusion run directory made by hand, with the columns a diffusion run will write:
// pollution_total and pollution_total_baseline in timeseries.csv and a 29 × 29 sensor grid.
void write_diffusion_run(const fs::path& dir) {
  fs::create_directories(dir);
  const json summary = {
      {"masnet_version", "test"},
      {"seed", 7},
      {"sim_time_s", 4.0},
      {"wall_time_s", 0.5},
      {"events", 1000},
      {"fingerprint", "0123456789abcdef"},
      {"scenario",
       {{"name", "pollution_by_hand"},
        {"robots", 4},
        {"sensors", 841},
        {"sensor_layout", "grid"},
        {"resolved",
         {{"domain", {{"rectangle", {0, 0, 1, 1}}, {"polygon", json::array()}}},
          {"field",
           {{"kind", "diffusion"},
            {"sources",
             {{{"start", {0.21, 0.79}}, {"velocity", {0.06, 0.0}}},
              {{"start", {0.8, 0.21}}, {"velocity", {-0.06, 0.0}}}}}}}}}}},
      {"messages",
       {{"total", {{"count", 40}, {"bytes", 800}}},
        {"by_type", {{"POSITION", {{"count", 40}, {"bytes", 800}}}}}}},
      {"energy_j", {{"total", 0.01}, {"radio_tx", 0.004}, {"radio_rx", 0.006}}},
      {"protocol", {{"name", "oracle"}, {"updates", 80}}},
      {"pollution",
       {{"peak", 5.0},
        {"final", 1.8},
        {"final_over_peak", 0.36},
        {"baseline", {{"peak", 6.0}, {"final", 5.5}, {"final_over_peak", 0.92}}}}}};
  std::ofstream(dir / "summary.json") << summary.dump(2);

  const std::vector<std::pair<double, double>> robots{
      {1 / 3.0, 1 / 3.0}, {1 / 3.0, 2 / 3.0}, {2 / 3.0, 1 / 3.0}, {2 / 3.0, 2 / 3.0}};
  std::ofstream ts(dir / "timeseries.csv");
  ts << "t_s,coverage_cost,mean_dist_to_centroid,max_dist_to_centroid,mean_radius,messages,bytes,"
        "energy_j,updates,"
        "cell_correctness,pollution_total,pollution_total_baseline\n";
  std::ofstream tr(dir / "trajectories.csv");
  tr << "t_s,robot,x,y,vx,vy,radius,cx,cy\n";
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.1 * k;
    const double with = 20 * t * std::exp(-t), without = 20 * (1 - std::exp(-t));
    ts << fmt::format("{},{},0.01,0.02,0.5,{},{},{},{},1,{},{}\n", t, 1.0 / (1 + t), 10 * k,
                      200 * k, 0.00025 * k, 2 * k, with, without);
    for (std::size_t i = 0; i < robots.size(); ++i)
      tr << fmt::format("{},{},{},{},0,0,0.5,0.5,0.5\n", t, i, robots[i].first + 0.02 * t,
                        robots[i].second + 0.01 * t * static_cast<double>(i));
  }
  std::ofstream nodes(dir / "nodes.csv");
  nodes << "node,role,index,x,y,alive,died_at_s,energy_j\n";
  std::ofstream sensors(dir / "sensors.csv");
  sensors << "index,x,y,area\n";
  std::vector<std::pair<double, double>> grid;
  for (std::size_t i = 0; i < robots.size(); ++i)
    nodes << fmt::format("{},robot,{},{},{},1,,{}\n", i, i, robots[i].first, robots[i].second,
                         0.001 * static_cast<double>(i + 1));
  for (int j = 0; j < 29; ++j)
    for (int i = 0; i < 29; ++i) {
      const double x = (i + 1) / 30.0, y = (j + 1) / 30.0;
      const std::size_t s = grid.size();
      grid.emplace_back(x, y);
      sensors << fmt::format("{},{},{},{}\n", s, x, y, 1.0 / 900);
      nodes << fmt::format("{},sensor,{},{},{},1,,{}\n", s + 4, s, x, y,
                           1e-5 * static_cast<double>(s % 7));
    }
  json snapshots = json::array();
  for (double t : {2.6, 3.1}) {
    json readings = json::array();
    for (const auto& [x, y] : grid) {
      const double d1 = std::hypot(x - 0.21 - 0.06 * t, y - 0.79),
                   d2 = std::hypot(x - 0.8 + 0.06 * t, y - 0.21);
      readings.push_back(std::exp(-d1 * d1 / 0.02) + 0.5 * std::exp(-d2 * d2 / 0.03));
    }
    json rs = json::array();
    for (const auto& [x, y] : robots)
      rs.push_back(
          {{"position", {x, y}},
           {"target", {x + 0.01, y}},
           {"radius", 0.4},
           {"cell",
            {{x - 0.1, y - 0.1}, {x + 0.1, y - 0.1}, {x + 0.1, y + 0.1}, {x - 0.1, y + 0.1}}},
           {"oracle_cell", {{x - 0.1, y - 0.1}, {x + 0.1, y - 0.1}, {x + 0.1, y + 0.1}}}});
    // The PDE grid: 31 × 31 nodes with the walls (u = 0 there), at 3.1 s only.
    json field = nullptr;
    if (t > 3) {
      std::vector<double> values;
      for (int j = 0; j <= 30; ++j)
        for (int i = 0; i <= 30; ++i) {
          const double x = i / 30.0, y = j / 30.0, d = std::hypot(x - 0.4, y - 0.79);
          values.push_back(i == 0 || j == 0 || i == 30 || j == 30 ? 0.0 : std::exp(-d * d / 0.02));
        }
      field = {{"nx", 31},  {"ny", 31},  {"x0", 0.0},       {"y0", 0.0},
               {"x1", 1.0}, {"y1", 1.0}, {"values", values}};
    }
    snapshots.push_back({{"t", t},
                         {"field", field},
                         {"robots", rs},
                         {"readings", readings},
                         {"sources",
                          {{{"position", {0.21 + 0.06 * t, 0.79}}, {"heading", {1, 0}}},
                           {{"position", {0.8 - 0.06 * t, 0.21}}, {"heading", {-1, 0}}}}}});
  }
  std::ofstream(dir / "snapshots.json") << snapshots.dump();
}

}  // namespace

TEST_CASE("A diffusion run gets the pollution curve and field maps with robots", "[scenarios]") {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("masnet-test-diffusion-{}", ::getpid());
  fs::remove_all(dir);
  write_diffusion_run(dir);
  const fs::path report = render_run_directory(dir);
  CHECK(report == fs::absolute(dir / "report.html"));
  for (const char* stem :
       {"pollution", "field_t2.6", "field_t3.1", "pollution_surface_t2.6", "pollution_surface_t3.1",
        "snapshot_t2.6", "snapshot_t3.1", "trajectories", "coverage_cost", "radius", "messages",
        "energy", "correctness"}) {
    check_png(dir / "figures" / (std::string(stem) + ".png"));
    check_svg(dir / "figures" / (std::string(stem) + ".svg"));
  }
  CHECK_FALSE(fs::exists(dir / "figures" / "tracking.png"));  // no tracking columns
  // Field maps show no cells; the snapshot figures show one per robot.
  CHECK(count(slurp(dir / "figures" / "field_t2.6.svg"), "class=\"cell\"") == 0);
  CHECK(count(slurp(dir / "figures" / "snapshot_t2.6.svg"), "class=\"cell\"") == 4);
  const std::string html = slurp(report);
  CHECK(html.find("id=\"results-pollution\"") != std::string::npos);
  CHECK(html.find("final_over_peak") != std::string::npos);
  CHECK(html.find("\"chart-pollution\"") != std::string::npos);
  CHECK(html.find("\"pollution_total_baseline\"") != std::string::npos);
  CHECK(count(html, "class=\"snapshot-frame\"") == 2);
  fs::remove_all(dir);
}

TEST_CASE("Our CSV files read back by column, as numbers and as text", "[scenarios]") {
  const fs::path path =
      fs::temp_directory_path() / fmt::format("masnet-test-table-{}.csv", ::getpid());
  std::ofstream(path) << "a,b,role\n1,2.5,robot\n3,,sensor\n-1e-05,inf,sensor\n";
  const Table t = Table::read(path);
  REQUIRE(t.rows() == 3);
  CHECK(t.names() == std::vector<std::string>{"a", "b", "role"});
  CHECK(t.column("a") == std::vector<double>{1, 3, -1e-5});
  CHECK(t.column("b")[0] == 2.5);
  CHECK(std::isnan(t.column("b")[1]));
  CHECK(std::isinf(t.column("b")[2]));
  CHECK(t.text("role") == std::vector<std::string>{"robot", "sensor", "sensor"});
  CHECK(t.text("a").empty());  // all numbers: no text kept
  CHECK_FALSE(t.has("c"));
  CHECK_THROWS_AS(t.column("c"), std::out_of_range);
  std::ofstream(path) << "a,b\n1,2\n3\n";
  CHECK_THROWS_WITH(Table::read(path), Catch::Contains(":3: 1 fields, the header has 2"));
  fs::remove(path);
  CHECK_THROWS_WITH(Table::read(path), Catch::Contains("cannot read"));
}

TEST_CASE("Snapshot figure names carry the time with at least one decimal", "[scenarios]") {
  CHECK(snapshot_time_label(2.0) == "2.0");
  CHECK(snapshot_time_label(2.6) == "2.6");
  CHECK(snapshot_time_label(0.5) == "0.5");
  CHECK(snapshot_time_label(0.125) == "0.125");
  CHECK(snapshot_time_label(10.0) == "10.0");
  CHECK(snapshot_time_label(0.49999999999) == "0.5");
}

TEST_CASE("Axis ticks are round numbers with short labels", "[scenarios]") {
  using namespace masnet::scenarios::plot;
  const std::vector<double> ticks = nice_ticks(0.0, 1.0, 5);
  REQUIRE(ticks.size() == 6);
  for (std::size_t i = 0; i < ticks.size(); ++i)
    CHECK(ticks[i] == Approx(0.2 * static_cast<double>(i)));
  const std::vector<double> inner = nice_ticks(0.45, 0.85, 6);  // steps of 0.1 inside the range
  REQUIRE(inner.size() == 4);
  CHECK(inner.front() == Approx(0.5));
  CHECK(inner.back() == Approx(0.8));
  CHECK(nice_ticks(-3.0, 3.0, 6) == std::vector<double>{-3, -2, -1, 0, 1, 2, 3});
  CHECK(log_ticks(3.0, 6400.0) == std::vector<double>{10, 100, 1000});
  CHECK(log_ticks(0.5, 20.0) == std::vector<double>{0.5, 1, 2, 5, 10, 20});
  CHECK(tick_label(0.25, 0.05) == "0.25");
  CHECK(tick_label(0.2, 0.2) == "0.2");
  CHECK(tick_label(3.0, 1.0) == "3");
  CHECK(tick_label(250000, 50000) == "250k");
  CHECK(tick_label(2500000, 500000) == "2.5M");
  CHECK(tick_label(1e-5, 1e-5) == "1e-5");
  CHECK(tick_label(1e-17, 0.1) == "0");
}

TEST_CASE("Colour scales clamp, and the log scale spreads decades evenly", "[scenarios]") {
  using namespace masnet::scenarios::plot;
  const ColourScale log{1.0, 1000.0, Scale::log};
  CHECK(log.unit(10.0) == Approx(1.0 / 3));
  CHECK(log.unit(100.0) == Approx(2.0 / 3));
  CHECK(log.unit(0.0) == 0.0);
  CHECK(log.unit(1e6) == 1.0);
  const ColourScale linear{0.0, 2.0, Scale::linear};
  CHECK(linear.unit(0.5) == Approx(0.25));
  CHECK(linear.unit(-1.0) == 0.0);
  // Light for low values, dark for high ones.
  const Rgb low = sequential(0.0), high = sequential(1.0);
  CHECK(low.r + low.g + low.b > 2.5);
  CHECK(high.r + high.g + high.b < 0.8);
}

TEST_CASE("SVG post-processing renumbers Cairo's global ids and tags reserved strokes",
          "[scenarios]") {
  using namespace masnet::scenarios::plot;
  const std::string cairo_svg =
      "<defs><image id=\"image13\" width=\"4\"/></defs><g id=\"surface9\">"
      "<use xlink:href=\"#image13\"/>"
      "<path style=\"fill:none;stroke:rgb(2%,2%,2%);stroke-opacity:1;\" d=\"M 0 0 L 1 1 Z\"/>"
      "<path style=\"fill:none;stroke:rgb(16%,44%,88%);stroke-dasharray:5,3.5;\" d=\"M 0 0\"/>"
      "<path style=\"fill:rgb(2%,2%,2%);stroke:none;\" d=\"M 0 0\"/>"
      "<path style=\"fill:none;stroke:rgb(2%,2%,2%);\" d=\"M 1 1\"/></g>";
  const std::string out = finish_svg(cairo_svg, snapshot_svg_classes());
  CHECK(out.find("id=\"image1\"") != std::string::npos);
  CHECK(out.find("href=\"#image1\"") != std::string::npos);
  CHECK(out.find("id=\"surface1\"") != std::string::npos);
  CHECK(out.find("image13") == std::string::npos);
  CHECK(out.find("<path class=\"cell\" id=\"cell-0\" style=\"fill:none;stroke:rgb(2%,2%,2%)") !=
        std::string::npos);
  CHECK(out.find("<path class=\"cell\" id=\"cell-1\"") != std::string::npos);
  CHECK(out.find("<path class=\"oracle-cell\" id=\"oracle-cell-0\"") != std::string::npos);
  CHECK(count(out, "class=\"cell\"") == 2);  // a fill of the same colour is not a cell
}
