#include <catch2/catch.hpp>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

#include "headless_chromium.hpp"
#include "scenarios/report/figures.hpp"
#include "scenarios/report/report.hpp"
#include "short_run.hpp"
#include "text_files.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios;

namespace {

using masnet::test::count;
using masnet::test::slurp;

using masnet::test::ShortRun;

const ShortRun& short_run() {
  static const ShortRun run("report");
  return run;
}

// The page without the contents of its <script> elements (the inlined library's own text).
std::string markup_only(const std::string& html) {
  std::string out;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t open = html.find("<script", pos);
    if (open == std::string::npos) break;
    const std::size_t body = html.find('>', open);
    const std::size_t close = html.find("</script>", body);
    REQUIRE(close != std::string::npos);
    out.append(html, pos, body + 1 - pos);
    pos = close;
  }
  out.append(html, pos, std::string::npos);
  return out;
}

const std::vector<std::string> kSections{"metadata", "scenario",  "messages", "protocol",
                                         "results",  "snapshots", "charts",   "figures"};

void check_sections(const std::string& html) {
  for (const std::string& id : kSections) {
    INFO(id);
    CHECK(count(html, "<section id=\"" + id + "\">") == 1);
    CHECK(count(html, "href=\"#" + id + "\"") == 1);  // listed in the navigation
  }
}

// No reference leaves the file: every src is a data: URI, every href an in-page anchor.
void check_self_contained(const std::string& html) {
  const std::string markup = markup_only(html);
  // A plain scan: std::regex recurses per character and overflows the stack on data URIs.
  std::size_t sources = 0;
  for (const std::string name : {"src", "href"}) {
    for (std::size_t at = markup.find(name + "="); at != std::string::npos;
         at = markup.find(name + "=", at + 1)) {
      const char before = at > 0 ? markup[at - 1] : ' ';
      if (std::isalnum(static_cast<unsigned char>(before)) || before == '-' || before == '_')
        continue;
      std::size_t start = at + name.size() + 1;
      if (start < markup.size() && (markup[start] == '"' || markup[start] == '\'')) ++start;
      const std::string value = markup.substr(start, 40);
      INFO(name << "=" << value);
      if (name == "src") {
        CHECK(value.rfind("data:image/", 0) == 0);
        ++sources;
      } else {
        CHECK(value.rfind("#", 0) == 0);
      }
    }
  }
  CHECK(sources > 0);
  CHECK(markup.find("http://") == std::string::npos);
  CHECK(markup.find("https://") == std::string::npos);
  CHECK(markup.find("<link") == std::string::npos);
  CHECK(markup.find("url(") == std::string::npos);
}

}  // namespace

TEST_CASE(
    "The report has every section, inline figures, a snapshot slider and no external reference",
    "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  const std::string html = slurp(run.dir / "report.html");
  CHECK(html.find("<title>masnet report: acoustic_tracking (seed 1)</title>") != std::string::npos);
  check_sections(html);
  check_self_contained(html);
  // Metadata and tables from summary.json.
  const std::string summary = slurp(run.dir / "summary.json");
  CHECK(html.find("id=\"resolved-scenario\"") != std::string::npos);
  CHECK(html.find("id=\"messages-by-type\"") != std::string::npos);
  CHECK(html.find("id=\"energy\"") != std::string::npos);
  CHECK(html.find("id=\"protocol-statistics\"") != std::string::npos);
  CHECK(html.find("id=\"results-tracking\"") != std::string::npos);
  CHECK(html.find("id=\"results-coverage\"") != std::string::npos);
  // The slider switches between the two snapshots; the first one shows.
  CHECK(html.find("id=\"snapshot-slider\" min=\"0\" max=\"1\"") != std::string::npos);
  CHECK(count(html, "class=\"snapshot-frame\"") == 2);
  CHECK(html.find("<div class=\"snapshot-frame\" data-t=\"0.5\" id=\"snapshot-0.5\">") !=
        std::string::npos);
  CHECK(html.find("<div class=\"snapshot-frame\" data-t=\"1.0\" id=\"snapshot-1.0\" hidden>") !=
        std::string::npos);
  // Every non-snapshot figure inline.
  for (const char* stem :
       {"trajectories", "coverage_cost", "tracking", "radius", "messages", "energy", "correctness"})
    CHECK(html.find(fmt::format("<figure id=\"figure-{}\">", stem)) != std::string::npos);
  if (find_chartjs({})) {
    CHECK(count(html, "<canvas id=\"chart-") >= 8);
    CHECK(html.find("chart-tracking") != std::string::npos);
    CHECK(html.find("id=\"charts-unavailable\"") == std::string::npos);
  } else {
    WARN("libjs-chart.js is not installed: the report was written without interactive charts");
    CHECK(html.find("id=\"charts-unavailable\"") != std::string::npos);
  }
}

TEST_CASE(
    "Without a usable Chart.js the report is still written and says that charts are unavailable",
    "[scenarios]") {
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  RunData data = load_run_data(run.dir);
  const fs::path figures = run.dir / "figures";
  const std::vector<FigureInfo> list{{"snapshot_t0.5", "snapshot", "a snapshot", 0.5},
                                     {"trajectories", "trajectories", "paths"}};
  data.dir = run.base / "no-charts";
  fs::create_directories(data.dir);

  SECTION("the file is missing") {
    const fs::path report =
        write_report(data, list, figures, ReportOptions{"/nonexistent/chart.min.js"});
    const std::string html = slurp(report);
    check_sections(html);
    check_self_contained(html);
    CHECK(html.find("id=\"charts-unavailable\"") != std::string::npos);
    CHECK(html.find("Interactive charts are unavailable") != std::string::npos);
    CHECK(html.find("libjs-chart.js") != std::string::npos);
    CHECK(html.find("<canvas id=\"chart-") == std::string::npos);
    CHECK(html.find("<figure id=\"figure-trajectories\">") != std::string::npos);
  }
  SECTION("the file is an ES module, which a plain script cannot load") {
    const fs::path esm = run.base / "chart.esm.js";
    std::ofstream(esm)
        << "import { a as b } from './chunks/helpers.segment.js';\nexport { b as Chart };\n";
    const std::string html = slurp(write_report(data, list, figures, ReportOptions{esm}));
    CHECK(html.find("id=\"charts-unavailable\"") != std::string::npos);
    CHECK(html.find("not a UMD build") != std::string::npos);
    CHECK(html.find("./chunks/helpers") == std::string::npos);
  }
}

TEST_CASE("The report opens in headless Chromium without errors and draws its charts",
          "[scenarios][chromium]") {
  MASNET_REQUIRE_TOOL(fs::exists(masnet::test::kChromium),
                      "/usr/bin/chromium (apt-get install chromium)");
  MASNET_REQUIRE_TOOL(find_chartjs({}), "Chart.js (apt-get install libjs-chart.js)");
  const ShortRun& run = short_run();
  REQUIRE(run.status == 0);
  const fs::path shot = run.base / "screenshot.png";
  const masnet::test::HeadlessPage opened =
      masnet::test::open_headless(run.dir / "report.html", run.base, shot);
  const std::string& page = opened.dom;
  const std::string& messages = opened.log;
  INFO(messages.substr(0, 4000));
  REQUIRE(opened.status == 0);
  CHECK(page.find("<title>masnet report: acoustic_tracking (seed 1)</title>") != std::string::npos);
  // The page's own error trap stayed empty and hidden, and the chart code ran to its end.
  CHECK(page.find("<pre id=\"page-errors\" hidden=\"\"></pre>") != std::string::npos);
  CHECK(messages.find("Uncaught") == std::string::npos);
  const std::size_t body = page.find("<body data-charts=\"");
  REQUIRE(body != std::string::npos);
  CHECK(std::stoi(page.substr(body + 19, 4)) >= 8);
  CHECK(count(page, "<canvas id=\"chart-") >= 8);
  // The replay player ran: 1 s at a frame every 0.02 s.
  CHECK(page.find("data-replay-frames=\"51\"") != std::string::npos);
  // Chart.js sizes every canvas it draws on.
  CHECK(count(page, "style=\"display: block; box-sizing: border-box;") >= 8);
  const std::string png = slurp(shot);
  CHECK(png.size() > 20000);
  CHECK(png.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0);
}
