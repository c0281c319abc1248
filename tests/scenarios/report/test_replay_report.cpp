#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "scenarios/report/replay_section.hpp"
#include "scenarios/report/report.hpp"
#include "scenarios/report/web_assets.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using masnet::test::count;
using masnet::test::slurp;
using namespace masnet::scenarios;
using nlohmann::json;

namespace {

// The paper's acoustic scenario through the CLI with `settings` (--set ...), in a folder of its
// own removed at exit.
struct AcousticRun {
  fs::path base, dir;
  int status = -1;
  AcousticRun(const std::string& tag, const std::string& settings) {
    base = fs::temp_directory_path() / fmt::format("masnet-test-replay-{}-{}", tag, ::getpid());
    fs::remove_all(base);
    fs::create_directories(base);
    dir = base / "run";
    status = std::system(fmt::format("'{}/scenarios/masnet' run "
                                     "'{}/scenarios/paper/acoustic_tracking.yaml' --out '{}' {} "
                                     "--quiet > '{}' 2>&1",
                                     MASNET_BINARY_DIR, MASNET_SOURCE_DIR, dir.string(), settings,
                                     (base / "output.txt").string())
                             .c_str());
  }
  ~AcousticRun() {
    std::error_code ec;
    fs::remove_all(base, ec);
  }
  AcousticRun(const AcousticRun&) = delete;
  AcousticRun& operator=(const AcousticRun&) = delete;
};

int render(const fs::path& dir) {
  return std::system(
      fmt::format("'{}/scenarios/masnet' render '{}' --quiet", MASNET_BINARY_DIR, dir.string())
          .c_str());
}

// The text of <script type="application/json" id="replay-data"> in `html`.
std::string replay_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"replay-data\">";
  const std::size_t start = html.find(open);
  if (start == std::string::npos) return {};
  const std::size_t end = html.find("</script>", start);
  return html.substr(start + open.size(), end - start - open.size());
}

bool ascii_only(std::string_view text) {
  for (char c : text)
    if (static_cast<unsigned char>(c) > 0x7e || (c < 0x20 && c != '\n')) return false;
  return true;
}

}  // namespace

TEST_CASE("The full acoustic run's report replays every frame of replay.json within 5 MB",
          "[scenarios]") {
  const AcousticRun run("full", "");
  REQUIRE(run.status == 0);
  const std::string html = slurp(run.dir / "report.html");
  const auto bytes = fs::file_size(run.dir / "report.html");
  INFO("report.html: " << bytes << " bytes");
  CHECK(bytes < 5'000'000);

  CHECK(count(html, "<section id=\"replay\">") == 1);
  CHECK(count(html, "href=\"#replay\"") == 1);
  CHECK(count(html, "<canvas id=\"replay-canvas\"") == 1);
  for (const char* id : {"replay-play", "replay-speed", "replay-scrubber", "replay-time",
                         "replay-raster", "replay-oracle", "replay-trails"})
    CHECK(count(html, fmt::format("id=\"{}\"", id)) == 1);
  CHECK(count(html, "global.MasnetScene = ") == 1);
  CHECK(html.find("<option value=\"0.25\">") != std::string::npos);
  CHECK(html.find("<option value=\"8\">") != std::string::npos);

  // The inlined frames are replay.json's, all of them: 5 s at one frame every 0.02 s.
  const json inlined = json::parse(replay_data(html));
  std::ifstream file(run.dir / "replay.json");
  const json written = json::parse(file);
  CHECK(inlined == written);
  CHECK(written["frames"].size() == 251);
  CHECK(html.find(fmt::format("max=\"{}\" step=\"1\" value=\"0\" aria-label=\"replay frame\"",
                              written["frames"].size() - 1)) != std::string::npos);

  SECTION("masnet render writes the same page from the files") {
    fs::remove(run.dir / "report.html");
    REQUIRE(render(run.dir) == 0);
    CHECK(slurp(run.dir / "report.html") == html);
  }
  SECTION("without replay.json masnet render writes the report without a replay") {
    fs::remove(run.dir / "replay.json");
    REQUIRE(render(run.dir) == 0);
    const std::string again = slurp(run.dir / "report.html");
    CHECK(again.find("id=\"replay") == std::string::npos);
    CHECK(again.find("href=\"#replay\"") == std::string::npos);
    CHECK(again.find("MasnetScene") == std::string::npos);
    CHECK(count(again, "<section id=\"snapshots\">") == 1);
  }
  SECTION("a replay.json that is not whole stops masnet render with its name") {
    std::ofstream(run.dir / "replay.json") << "{\"header\": {}, \"frames\": [";
    CHECK_THROWS_WITH(load_run_data(run.dir), Catch::Contains("replay.json"));
    std::ofstream(run.dir / "replay.json") << "{\"frames\": []}";
    CHECK_THROWS_WITH(load_run_data(run.dir), Catch::Contains("replay.json"));
  }
}

TEST_CASE("A run with output.replay false has no replay.json and a report without a replay",
          "[scenarios]") {
  const AcousticRun run(
      "off", "--set duration=0.5 --set 'output.snapshots=[0.5]' --set output.replay=false");
  REQUIRE(run.status == 0);
  CHECK_FALSE(fs::exists(run.dir / "replay.json"));
  const std::string html = slurp(run.dir / "report.html");
  CHECK(count(html, "<section id=\"charts\">") == 1);
  CHECK(html.find("id=\"replay") == std::string::npos);
  CHECK(html.find("MasnetScene") == std::string::npos);
  CHECK(html.find(std::string(replay_style())) == std::string::npos);
}

TEST_CASE("The replay's frames are inlined so that no text in them can end the script element",
          "[scenarios]") {
  RunData run;
  run.replay = {
      {"header", {{"name", "a </script><!-- name"}, {"steps", 10000}}},
      {"frames", json::array({{{"t", 0.0}, {"p", {1, 2}}}, {{"t", 0.5}, {"p", {3, 4}}}})}};
  REQUIRE(has_replay_section(run));
  const std::string section = replay_section(run);
  const std::string data = replay_data(section);
  CHECK(data.find('<') == std::string::npos);
  CHECK(json::parse(data) == run.replay);
  CHECK(section.find("2 frames, one every 0.5 s") != std::string::npos);

  run.replay["frames"] = json::array();
  CHECK_FALSE(has_replay_section(run));
  CHECK(replay_section(run).empty());
  CHECK(replay_scripts(run).empty());
  CHECK_FALSE(has_replay_section(RunData{}));
}

TEST_CASE("The embedded scene drawing is the asset file, plain ASCII script text", "[scenarios]") {
  for (const auto& [code, file] : {std::pair{scene_view_js(), "scene_view.js"},
                                   std::pair{replay_player_js(), "replay_player.js"}}) {
    INFO(file);
    CHECK(code == slurp(fs::path(MASNET_SOURCE_DIR) / "scenarios/report/assets" / file));
    CHECK(ascii_only(code));
    CHECK(code.find("</") == std::string::npos);  // safe inside <script> as it is
    CHECK(code.find("import ") == std::string::npos);
    CHECK(code.find("fetch(") == std::string::npos);
    CHECK(code.find("http") == std::string::npos);
  }
  CHECK(scene_view_js().find("global.MasnetScene = {View: View") != std::string::npos);
}

TEST_CASE("chart_js_source hands out Chart.js as the report inlines it, or nothing",
          "[scenarios]") {
  CHECK(chart_js_source(ReportOptions{"/nonexistent/chart.umd.js"}).empty());
  if (!find_chartjs({})) {
    WARN("libjs-chart.js is not installed");
    return;
  }
  const std::string code = chart_js_source();
  std::string why_not;
  const auto library = load_chartjs({}, why_not);
  REQUIRE(library);
  CHECK(code == library->code);
  CHECK(code.size() > 100000);
  CHECK(code.find("</script") == std::string::npos);
}
