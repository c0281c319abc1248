// A sweep file's report.reference_lines: read and checked with positioned errors, drawn across
// the metric's sensitivity figure where the axis mapping puts them, and embedded in report.html.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "scenarios/sweep/sweep.hpp"
#include "scenarios/sweep/sweep_figures.hpp"
#include "sweep_helpers.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;
using masnet::test::count;
using masnet::test::fresh_dir;
using masnet::test::slurp;
using masnet::test::tiny_sweep_text;

namespace {

const std::string kSource = MASNET_SOURCE_DIR;
const std::string kInline = kSource + "/scenarios/sweeps/inline.yaml";
const std::string kHead =
    "base: ../paper/acoustic_tracking.yaml\n"
    "vary:\n"
    "  radio.loss: [0, 0.25]\n"
    "  protocol.kind: [oracle, gabriel]\n";

std::vector<std::string> errors(const std::string& text) {
  return masnet::test::sweep_errors(text, kInline);
}

}  // namespace

TEST_CASE("Sweep files declare reference lines for the report", "[scenarios]") {
  SweepLoad loaded =
      load_sweep_text(kHead +
                          "report:\n"
                          "  reference_lines:\n"
                          "    - {metric: messages.total.count, value: 1200, label: \"a budget\"}\n"
                          "    - {metric: messages.total.count, value: 800, x: radio.loss}\n"
                          "    - {metric: energy_j.total, value: 0.5, x: protocol.kind}\n",
                      kInline);
  REQUIRE(loaded.sweep);
  const auto& lines = loaded.sweep->reference_lines;
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].metric == "messages.total.count");
  CHECK(lines[0].value == 1200);
  CHECK(lines[0].label == "a budget");
  CHECK(lines[0].x == "radio.loss");  // the first varied factor
  CHECK(lines[1].label == "reference 800");
  CHECK(lines[2].x == "protocol.kind");
  // No report section, or an empty one: no lines.
  CHECK(load_sweep_text(kHead, kInline).sweep->reference_lines.empty());
  CHECK(load_sweep_text(kHead + "report: {}\n", kInline).sweep->reference_lines.empty());
}

TEST_CASE("Bad reference lines get file:line:col errors", "[scenarios]") {
  const std::string f = kInline;
  CHECK(errors(kHead + "report: [1, 2]\n") ==
        std::vector<std::string>{
            f + ":5:9: report: expected a mapping like {reference_lines: [{metric: "
                "pollution.final_over_peak, value: 0.36, label: \"the paper\"}]}"});
  CHECK(errors(kHead + "report:\n  reference_line: []\n") ==
        std::vector<std::string>{f + ":6:3: unknown key 'reference_line' in 'report' (did you mean "
                                     "'reference_lines'?)"});
  CHECK(errors(kHead + "report:\n  reference_lines: {metric: energy_j.total}\n") ==
        std::vector<std::string>{f +
                                 ":6:20: report.reference_lines: expected a list, got a mapping"});
  CHECK(errors(kHead +
               "report:\n  reference_lines:\n    - {metric: energy_j.total, value: high}\n") ==
        std::vector<std::string>{
            f + ":7:39: report.reference_lines[0].value: expected a number, got 'high'"});
  CHECK(errors(kHead + "report:\n  reference_lines:\n    - {metric: energy_j.totl, value: 1}\n") ==
        std::vector<std::string>{f + ":7:16: report.reference_lines[0].metric: expected one of " +
                                 [] {
                                   std::string all;
                                   for (const auto& m : sweep_report_metrics())
                                     all += (all.empty() ? "" : ", ") + std::string(m.key);
                                   return all;
                                 }() +
                                 ", got 'energy_j.totl' (did you mean 'energy_j.total'?)"});
  CHECK(errors(kHead + "report:\n  reference_lines:\n"
                       "    - {metric: energy_j.total, value: 1, colour: red}\n") ==
        std::vector<std::string>{f + ":7:42: unknown key 'colour' in 'report.reference_lines[0]'"});
  CHECK(errors(kHead + "report:\n  reference_lines:\n    - {metric: energy_j.total}\n") ==
        std::vector<std::string>{
            f + ":7:7: report.reference_lines[0].value: missing (a reference line needs a metric "
                "and a value, e.g. {metric: pollution.final_over_peak, value: 0.36})"});
  CHECK(errors(kHead + "report:\n  reference_lines:\n"
                       "    - {metric: energy_j.total, value: 1, x: radio.los}\n") ==
        std::vector<std::string>{
            f + ":7:45: report.reference_lines[0].x: 'radio.los' is not a varied parameter "
                "with more than one value (varied: radio.loss, protocol.kind) (did you mean "
                "'radio.loss'?)"});
  CHECK(errors(kHead + "report:\n  reference_lines:\n"
                       "    - {metric: energy_j.total, value: 1}\n"
                       "    - {metric: energy_j.total, value: 2, x: protocol.kind}\n") ==
        std::vector<std::string>{
            f + ":8:45: report.reference_lines[1].x: the lines of one metric share its figure "
                "and x axis: 'protocol.kind' here, 'radio.loss' in report.reference_lines[0]"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\n"
               "report:\n  reference_lines:\n    - {metric: energy_j.total, value: 1}\n") ==
        std::vector<std::string>{
            f + ":4:7: report.reference_lines[0].x: this sweep varies nothing with more than "
                "one value, so there is no parameter to draw the metric against"});
}

namespace {

// The y of the first "M x y L x y" path of class `name` in an SVG, and its two x.
struct Segment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
std::vector<Segment> segments_of_class(const std::string& svg, const std::string& name) {
  std::vector<Segment> out;
  for (std::size_t at = svg.find("class=\"" + name + "\""); at != std::string::npos;
       at = svg.find("class=\"" + name + "\"", at + 1)) {
    const std::size_t d = svg.find(" d=\"", at);
    Segment s;
    if (d != std::string::npos &&
        std::sscanf(svg.c_str() + d + 4, "M %lf %lf L %lf %lf", &s.x0, &s.y0, &s.x1, &s.y1) == 4)
      out.push_back(s);
  }
  return out;
}

}  // namespace

TEST_CASE("A reference line is drawn at the y the axis mapping gives its value", "[scenarios]") {
  const fs::path dir = fresh_dir("reference-figure");
  fs::create_directories(dir);
  SweepReportInput in;
  in.axes.push_back({"control.gain", {"1", "3"}, {1, 3}, true});
  in.axes.push_back({"field.diffusion.boundary", {"dirichlet", "no_flux"}, {0, 0}, false});
  // Final/peak of four configurations, one seed each: 0.2 … 0.6.
  const std::vector<std::pair<std::vector<std::size_t>, double>> configs{
      {{0, 0}, 0.5}, {{0, 1}, 0.6}, {{1, 0}, 0.2}, {{1, 1}, 0.45}};
  for (const auto& [points, value] : configs) {
    SweepReportRun run;
    run.ok = true;
    run.points = points;
    run.metrics["pollution.final_over_peak"] = value;
    in.runs.push_back(run);
  }
  in.reference_lines.push_back({"pollution.final_over_peak", 0.36, "the paper", "control.gain"});
  const std::vector<SweepFigure> figures = write_sensitivity_figures(in, dir);
  REQUIRE(figures.size() == 1);
  CHECK(figures[0].stem == "sensitivity_pollution_final_over_peak");
  for (const char* ext : {".png", ".svg", ".pdf"})
    CHECK(fs::exists(dir / (figures[0].stem + ext)));
  const std::string svg = slurp(dir / (figures[0].stem + ".svg"));
  const std::vector<Segment> lines = segments_of_class(svg, "reference-line");
  REQUIRE(lines.size() == 1);
  // y range: the values 0.2 … 0.6 (and 0.36 inside), widened by 8 % of the span each way.
  const double lo = 0.2 - 0.08 * 0.4, hi = 0.6 + 0.08 * 0.4;
  const plot::Box f = kSensitivityFrame;
  const double y = f.y + f.h * (hi - 0.36) / (hi - lo);
  CHECK(lines[0].y0 == Approx(y).margin(1e-3));
  CHECK(lines[0].y1 == Approx(y).margin(1e-3));
  CHECK(lines[0].x0 == Approx(f.x).margin(1e-3));
  CHECK(lines[0].x1 == Approx(f.x + f.w).margin(1e-3));
  // A reference value outside the data widens the range to include it: now at the top.
  in.reference_lines[0].value = 0.9;
  write_sensitivity_figures(in, dir);
  const double hi2 = 0.9 + 0.08 * 0.7;
  const std::vector<Segment> top =
      segments_of_class(slurp(dir / (figures[0].stem + ".svg")), "reference-line");
  REQUIRE(top.size() == 1);
  CHECK(top[0].y0 == Approx(f.y + f.h * (hi2 - 0.9) / (hi2 - (0.2 - 0.08 * 0.7))).margin(1e-3));
  // Without reference lines, the figures of an earlier invocation go.
  in.reference_lines.clear();
  CHECK(write_sensitivity_figures(in, dir).empty());
  CHECK_FALSE(fs::exists(dir / (figures[0].stem + ".svg")));
  fs::remove_all(dir);
}

TEST_CASE("A tiny sweep with a reference line writes its figure and embeds it in report.html",
          "[scenarios]") {
  const fs::path base = fresh_dir("reference-sweep");
  const fs::path file = masnet::test::write_file(
      base / "sweep.yaml",
      tiny_sweep_text("vary:\n  radio.loss: [0, 0.2]\n"
                      "report:\n  reference_lines:\n"
                      "    - {metric: messages.total.count, value: 100, label: a budget}\n"));
  SweepLoad loaded = load_sweep(file.string());
  REQUIRE(loaded.sweep);
  SweepOptions options;
  options.out_dir = (base / "out").string();
  options.jobs = 2;
  REQUIRE(run_sweep_locally(*loaded.sweep, options).exit_code() == 0);
  const fs::path out = options.out_dir;
  for (const char* ext : {".png", ".svg", ".pdf"})
    CHECK(fs::exists(out / (std::string("sensitivity_messages_total_count") + ext)));
  CHECK(count(slurp(out / "sensitivity_messages_total_count.svg"), "class=\"reference-line\"") ==
        1);
  const std::string html = slurp(out / "report.html");
  CHECK(count(html, "<figure id=\"figure-sensitivity_messages_total_count\">") == 1);
  CHECK(count(html, "<img src=\"data:image/") == 1);
  CHECK(html.find("dashed across: a budget.") != std::string::npos);
  fs::remove_all(base);
}
