#include "scenarios/report/report.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "scenarios/output/output_file.hpp"
#include "scenarios/report/fault_tables.hpp"
#include "scenarios/report/geometry_table.hpp"
#include "scenarios/report/message_table.hpp"
#include "scenarios/report/replay_section.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using nlohmann::json;

std::string escape_html(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Text placed inside <script>: "</" would end the element early.
std::string escape_script(std::string s) {
  for (std::size_t at = s.find("</"); at != std::string::npos; at = s.find("</", at + 3))
    s.replace(at, 2, "<\\/");
  return s;
}

std::string base64(std::string_view data) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, data.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = v << 8 | (k < n ? static_cast<unsigned char>(data[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63u] : '=';
  }
  return out;
}

// A scalar as a table cell: integers exactly, other numbers to six significant digits.
std::string cell(const json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number_float()) {
    const double d = v.get<double>();
    return std::isfinite(d) ? fmt::format("{:.6g}", d) : "—";
  }
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_string()) return escape_html(v.get<std::string>());
  if (v.is_null()) return "—";
  return "<code>" + escape_html(v.dump()) + "</code>";
}

// Rows "a.b.c | value" of every scalar (and short array) under `j`.
void flatten(const json& j, const std::string& prefix,
             std::vector<std::pair<std::string, std::string>>& rows) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items())
      flatten(value, prefix.empty() ? key : prefix + "." + key, rows);
    return;
  }
  rows.emplace_back(prefix, cell(j));
}

std::string key_value_table(const json& j, const std::string& id = {}) {
  std::vector<std::pair<std::string, std::string>> rows;
  flatten(j, "", rows);
  std::string out =
      id.empty() ? "<table class=\"kv\">\n" : "<table class=\"kv\" id=\"" + id + "\">\n";
  for (const auto& [k, v] : rows)
    out += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", escape_html(k), v);
  return out + "</table>\n";
}

// A figure as a data URI: the smaller of its SVG and PNG.
std::string figure_uri(const fs::path& figures_dir, const std::string& stem) {
  const fs::path svg = figures_dir / (stem + ".svg"), png = figures_dir / (stem + ".png");
  const bool has_svg = fs::exists(svg), has_png = fs::exists(png);
  if (has_svg && (!has_png || fs::file_size(svg) <= fs::file_size(png)))
    return "data:image/svg+xml;base64," + base64(read_file(svg));
  if (has_png) return "data:image/png;base64," + base64(read_file(png));
  return {};
}

std::string image(const fs::path& figures_dir, const FigureInfo& f) {
  const std::string uri = figure_uri(figures_dir, f.stem);
  if (uri.empty()) return "<p class=\"note\">missing figure " + escape_html(f.stem) + "</p>\n";
  return fmt::format(
      "<img src=\"{0}\" alt=\"{1}\" title=\"figures/{2}.svg, figures/{2}.png, figures/{2}.pdf\">\n",
      uri, escape_html(f.caption), escape_html(f.stem));
}

// Interactive charts: which time-series columns each one shows (only existing columns).
json chart_specs(const Table& ts) {
  struct Series {
    std::string column, label, colour;
    bool dashed = false, stepped = false;
  };
  struct Spec {
    std::string id, title, y;
    std::vector<Series> series;
    bool log = false;
  };
  std::vector<Series> groups;
  for (const std::string& name : ts.names())
    if (name.rfind("robots_target_", 0) == 0)
      groups.push_back({name, "target " + name.substr(14), "", false, true});
  const std::vector<Spec> specs{
      {"chart-coverage", "Coverage cost", "H", {{"coverage_cost", "coverage cost H", "#1f77b4"}}},
      {"chart-centroid",
       "Distance to the true centroid",
       "‖p − c‖ (world units)",
       {{"mean_dist_to_centroid", "mean", "#1f77b4"}, {"max_dist_to_centroid", "max", "#d62728"}}},
      {"chart-tracking",
       "Tracking error",
       "distance to nearest robot (world units)",
       {{"tracking_error_mean", "mean", "#1f77b4"}, {"tracking_error_max", "max", "#d62728"}}},
      {"chart-groups", "Robots per target", "robots", groups},
      {"chart-pollution",
       "Total pollution",
       "Σ u at the sensors",
       {{"pollution_total", "with control", "#d62728"},
        {"pollution_total_baseline", "without control", "#7f7f7f", true}}},
      {"chart-pollution-field",
       "Pollution on the PDE grid",
       "∫u dA, max u",
       {{"pollution_integral", "∫u dA, with control", "#d62728"},
        {"pollution_integral_baseline", "∫u dA, without control", "#7f7f7f", true},
        {"pollution_max", "max u", "#ff7f0e"}}},
      {"chart-neutraliser",
       "Neutraliser released (cumulative)",
       "amount",
       {{"neutraliser_used", "all robots", "#2ca02c"}}},
      {"chart-radius", "Mean radius", "R (world units)", {{"mean_radius", "mean R", "#000000"}}},
      {"chart-messages",
       "Messages sent (cumulative)",
       "messages",
       {{"messages", "messages", "#1f77b4"}}},
      {"chart-bytes", "Bytes sent (cumulative)", "bytes", {{"bytes", "bytes", "#ff7f0e"}}},
      {"chart-energy", "Radio energy (cumulative)", "J", {{"energy_j", "energy", "#d62728"}}},
      {"chart-correctness",
       "Cell correctness (all updates so far)",
       "share",
       {{"cell_correctness", "correct neighbour sets", "#2ca02c"}}},
      {"chart-alive",
       "Nodes up",
       "nodes",
       {{"alive_sensors", "sensors", "#1f77b4", false, true},
        {"alive_robots", "robots", "#ff7f0e", false, true}}},
      {"chart-twin",
       "Coverage cost beside the fault-free twin",
       "H",
       {{"coverage_cost", "with faults", "#1f77b4"},
        {"coverage_cost_twin", "fault-free twin", "#7f7f7f", true}}},
      {"chart-collisions",
       "Collisions (cumulative)",
       "receptions lost to overlap",
       {{"collisions", "collisions", "#9467bd"}}},
  };
  static const std::vector<std::string> kPalette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                 "#9467bd"};
  json out = json::array();
  for (const Spec& spec : specs) {
    json series = json::array();
    for (std::size_t k = 0; k < spec.series.size(); ++k) {
      const Series& s = spec.series[k];
      if (!ts.has(s.column)) continue;
      series.push_back({{"column", s.column},
                        {"label", s.label},
                        {"colour", s.colour.empty() ? kPalette[k % kPalette.size()] : s.colour},
                        {"dashed", s.dashed},
                        {"stepped", s.stepped}});
    }
    if (series.empty()) continue;
    out.push_back({{"id", spec.id},
                   {"title", spec.title},
                   {"y", spec.y},
                   {"log", spec.log},
                   {"series", series}});
  }
  return out;
}

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; margin: 0 auto; max-width: 1100px;
       padding: 0 1.2em 3em; color: #1b1b1b; line-height: 1.4; }
header { border-bottom: 2px solid #333; margin-bottom: 1em; }
h1 { margin: 0.6em 0 0.2em; font-size: 1.7em; }
h2 { margin-top: 1.6em; border-bottom: 1px solid #ccc; padding-bottom: 0.2em; }
nav a { margin-right: 1em; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.92em; }
th, td { border: 1px solid #d4d4d4; padding: 0.25em 0.6em; text-align: left; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
table.kv th { font-weight: normal; color: #444; background: #f6f6f6; }
thead th { background: #eee; }
pre { background: #f6f6f6; padding: 0.8em; overflow-x: auto; font-size: 0.85em; }
figure { margin: 1em 0 2em; }
figure img, .snapshot-frame img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { color: #444; font-size: 0.92em; }
.note { background: #fff5d6; border-left: 4px solid #e0a800; padding: 0.5em 0.8em; }
.charts { display: grid; grid-template-columns: repeat(auto-fill, minmax(480px, 1fr)); gap: 1em; }
.chart-box { position: relative; height: 300px; }
.slider { display: flex; align-items: center; gap: 1em; margin: 0.5em 0; }
.slider input { flex: 1; }
.snapshot-frame { display: flex; flex-wrap: wrap; gap: 1em; }
#page-errors { color: #a00; }
[hidden] { display: none !important; }
)";

// Runs first: records script errors, failed loads and console.error into #page-errors, so
// that a headless browser's DOM dump shows them.
constexpr const char* kErrorScript = R"(
(function () {
  var errors = [];
  window.masnetErrors = errors;
  function show() {
    var el = document.getElementById('page-errors');
    if (el) { el.textContent = errors.join('\n'); el.hidden = errors.length === 0; }
  }
  window.addEventListener('error', function (e) {
    if (e.target && e.target !== window && e.target.tagName) errors.push('failed to load ' + e.target.tagName);
    else errors.push('error: ' + (e.message || String(e)));
    show();
  }, true);
  window.addEventListener('unhandledrejection', function (e) { errors.push('unhandled rejection: ' + e.reason); show(); });
  var original = console.error;
  console.error = function () {
    errors.push('console.error: ' + Array.prototype.join.call(arguments, ' '));
    show();
    return original.apply(console, arguments);
  };
  document.addEventListener('DOMContentLoaded', show);
})();
)";

// The snapshot slider and the Chart.js charts, from the JSON in #timeseries-data.
constexpr const char* kReportScript = R"(
(function () {
  var frames = Array.prototype.slice.call(document.querySelectorAll('.snapshot-frame'));
  var slider = document.getElementById('snapshot-slider');
  var label = document.getElementById('snapshot-time');
  function showFrame(i) {
    frames.forEach(function (f, k) { f.hidden = k !== i; });
    if (label && frames[i]) label.textContent = 't = ' + frames[i].getAttribute('data-t') + ' s';
  }
  if (slider && frames.length) {
    slider.addEventListener('input', function () { showFrame(Number(slider.value)); });
    showFrame(Number(slider.value));
  }

  var data = JSON.parse(document.getElementById('timeseries-data').textContent);
  if (typeof Chart === 'undefined') { document.body.setAttribute('data-charts', '0'); return; }
  var made = 0;
  data.charts.forEach(function (spec) {
    var canvas = document.getElementById(spec.id);
    if (!canvas) return;
    var datasets = spec.series.map(function (s) {
      var ys = data.columns[s.column];
      return {
        label: s.label,
        data: data.t.map(function (t, i) { return { x: t, y: ys[i] }; }),
        borderColor: s.colour, backgroundColor: s.colour, borderWidth: 1.6,
        borderDash: s.dashed ? [6, 4] : [], pointRadius: 0, pointHitRadius: 6, stepped: s.stepped
      };
    });
    new Chart(canvas, {
      type: 'line',
      data: { datasets: datasets },
      options: {
        animation: false, responsive: true, maintainAspectRatio: false, parsing: false,
        interaction: { mode: 'nearest', axis: 'x', intersect: false },
        scales: {
          x: { type: 'linear', title: { display: true, text: 't (s)' } },
          y: { type: spec.log ? 'logarithmic' : 'linear', title: { display: true, text: spec.y } }
        },
        plugins: { title: { display: true, text: spec.title }, legend: { display: datasets.length > 1 } }
      }
    });
    ++made;
  });
  document.body.setAttribute('data-charts', String(made));
})();
)";

std::string energy_table(const json& summary) {
  if (!summary.contains("energy_j")) return "<p>No energy statistics.</p>\n";
  static const std::vector<std::pair<std::string, std::string>> kRows{
      {"total", "total, all nodes"},        {"radio_tx", "radio transmission"},
      {"radio_rx", "radio reception"},      {"idle", "idle listening"},
      {"robots_total", "robots, total"},    {"sensors_total", "sensors, total"},
      {"per_node_mean", "per node, mean"},  {"per_node_max", "per node, max"},
      {"per_sensor_max", "per sensor, max"}};
  const json& e = summary["energy_j"];
  std::string out =
      "<table id=\"energy\"><thead><tr><th>radio energy</th><th "
      "class=\"num\">J</th></tr></thead><tbody>\n";
  std::set<std::string> shown;
  for (const auto& [key, label] : kRows)
    if (e.contains(key)) {
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td></tr>\n", label, cell(e[key]));
      shown.insert(key);
    }
  for (const auto& [key, value] : e.items())
    if (!shown.count(key))
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td></tr>\n", escape_html(key),
                         cell(value));
  return out + "</tbody></table>\n";
}

}  // namespace

std::string figure_data_uri(const fs::path& dir, const std::string& stem) {
  return figure_uri(dir, stem);
}

std::optional<fs::path> find_chartjs(const ReportOptions& options) {
  if (!options.chartjs.empty()) {
    if (fs::is_regular_file(options.chartjs)) return options.chartjs;
    return std::nullopt;
  }
  if (const char* env = std::getenv("MASNET_CHARTJS"); env && *env) {
    if (fs::is_regular_file(env)) return fs::path(env);
    return std::nullopt;
  }
  for (const char* name : {"chart.umd.js", "chart.min.js", "chart.js"}) {
    const fs::path p = fs::path("/usr/share/javascript/chart.js") / name;
    if (fs::is_regular_file(p)) return p;
  }
  return std::nullopt;
}

std::optional<ChartLibrary> load_chartjs(const ReportOptions& options, std::string& why_not) {
  const std::optional<fs::path> path = find_chartjs(options);
  if (!path) {
    why_not =
        "Chart.js was not found (looked for /usr/share/javascript/chart.js/chart.umd.js, "
        "chart.min.js and "
        "chart.js; $MASNET_CHARTJS overrides). Install Debian's libjs-chart.js (scripts/setup "
        "does) and run "
        "<code>masnet render</code> on this directory again.";
    return std::nullopt;
  }
  std::string code;
  try {
    code = read_file(*path);
  } catch (const std::exception& e) {
    why_not = escape_html(e.what());
    return std::nullopt;
  }
  // A plain <script> needs the UMD build, which defines the global `Chart`.
  const std::string head = code.substr(0, 4096);
  if (head.find("typeof exports") == std::string::npos &&
      head.find("define.amd") == std::string::npos &&
      head.find("globalThis") == std::string::npos) {
    why_not = "'" + escape_html(path->string()) +
              "' is not a UMD build of Chart.js (an ES module cannot be inlined "
              "with its imports).";
    return std::nullopt;
  }
  std::string version;
  if (const std::size_t at = head.find("Chart.js v"); at != std::string::npos)
    version = head.substr(at + 10, head.find_first_of(" \n\r*", at + 10) - at - 10);
  return ChartLibrary{escape_script(std::move(code)),
                      fmt::format("Interactive charts: Chart.js {} (MIT licence), inlined from {}.",
                                  escape_html(version.empty() ? "(version unknown)" : version),
                                  escape_html(path->string()))};
}

fs::path write_report(const RunData& run, const std::vector<FigureInfo>& figures,
                      const fs::path& figures_dir, const ReportOptions& options) {
  const json& s = run.summary;
  const json scenario = s.value("scenario", json::object());
  const std::string title =
      fmt::format("masnet report: {} (seed {})", run.name, s.value("seed", json()).dump());
  std::string why_no_charts;
  const std::optional<ChartLibrary> chartjs = load_chartjs(options, why_no_charts);

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>" << escape_html(title) << "</title>\n<style>" << kStyle
    << (has_replay_section(run) ? replay_style() : std::string_view()) << "</style>\n<script>"
    << kErrorScript << "</script>\n</head>\n<body>\n";

  h << "<header>\n<h1>" << escape_html(run.name) << "</h1>\n<p>masnet run report — seed "
    << escape_html(s.value("seed", json()).dump()) << ", " << cell(s.value("sim_time_s", json()))
    << " s simulated, " << escape_html(run.field_kind) << " field, protocol "
    << (s.contains("protocol") ? cell(s["protocol"].value("name", json())) : std::string("—"))
    << ".</p>\n"
    << "<nav><a href=\"#metadata\">Run</a><a href=\"#scenario\">Scenario</a><a "
       "href=\"#messages\">Messages and "
       "energy</a><a href=\"#protocol\">Protocol</a><a href=\"#results\">Results</a>"
    << (has_replay_section(run) ? "<a href=\"#replay\">Replay</a>" : "")
    << "<a href=\"#snapshots\">Snapshots</a>"
    << (has_lifetime_section(s) ? "<a href=\"#lifetime\">Lifetime and faults</a>" : "")
    << "<a href=\"#charts\">Time series</a><a "
       "href=\"#figures\">Figures</a></nav>\n"
    << "</header>\n";

  // Run metadata.
  const double wall = s.value("wall_time_s", 0.0);
  const double events = s.value("events", 0.0);
  h << "<section id=\"metadata\">\n<h2>Run</h2>\n<table class=\"kv\">\n";
  auto row = [&](const std::string& k, const std::string& v) {
    h << "<tr><th>" << k << "</th><td>" << v << "</td></tr>\n";
  };
  row("scenario", escape_html(run.name));
  row("scenario file", cell(scenario.value("source", json())));
  row("masnet version", cell(s.value("masnet_version", json())));
  row("seed", cell(s.value("seed", json())));
  row("simulated time", cell(s.value("sim_time_s", json())) + " s");
  row("wall time", cell(s.value("wall_time_s", json())) + " s");
  row("events", cell(s.value("events", json())));
  if (wall > 0) row("events per second", fmt::format("{:.4g}", events / wall));
  row("fingerprint", "<code>" + cell(s.value("fingerprint", json())) + "</code>");
  row("run key", "<code>" + cell(s.value("run_key", json())) + "</code>");
  row("sensors", cell(scenario.value("sensors", json())) + " (" +
                     cell(scenario.value("sensor_layout", json())) + ")");
  row("robots", cell(scenario.value("robots", json())));
  h << "</table>\n</section>\n";

  // The resolved scenario.
  h << "<section id=\"scenario\">\n<h2>Scenario</h2>\n<details>\n<summary>Resolved scenario (every "
       "key, defaults "
       "included; JSON)</summary>\n<pre id=\"resolved-scenario\">"
    << escape_html(scenario.value("resolved", json::object())
                       .dump(2, ' ', false, json::error_handler_t::replace))
    << "</pre>\n</details>\n</section>\n";

  h << "<section id=\"messages\">\n<h2>Messages, energy and computation</h2>\n<h3>Messages by "
       "type</h3>\n"
    << messages_table(s) << "<h3>Energy by category</h3>\n"
    << energy_table(s) << "<h3>Computation per update</h3>\n"
    << computation_table(s) << "</section>\n";

  h << "<section id=\"protocol\">\n<h2>Protocol</h2>\n"
    << (s.contains("protocol") ? key_value_table(s["protocol"], "protocol-statistics")
                               : "<p>No protocol statistics.</p>\n")
    << "</section>\n";

  // Results: every other section of summary.json (coverage, tracking, pollution, …).
  static const std::set<std::string> kShown{"scenario", "messages", "energy_j",
                                            "protocol", "lifetime", "twin"};
  h << "<section id=\"results\">\n<h2>Results</h2>\n";
  for (const auto& [key, value] : s.items()) {
    if (kShown.count(key) || !value.is_object()) continue;
    h << "<h3 id=\"results-" << escape_html(key) << "\">" << escape_html(key) << "</h3>\n"
      << key_value_table(value);
  }
  h << "</section>\n";

  h << replay_section(run);

  // Snapshots with a slider (for diffusion runs the field maps and surfaces beside the cells).
  std::vector<double> times;
  for (const FigureInfo& f : figures)
    if (f.kind == "snapshot") times.push_back(f.t_s);
  h << "<section id=\"snapshots\">\n<h2>Snapshots</h2>\n";
  if (times.empty()) {
    h << "<p class=\"note\">No snapshot figures (set <code>output.snapshots</code>, and keep "
         "<code>output.figures</code> on).</p>\n";
  } else {
    h << "<div class=\"slider\"><input type=\"range\" id=\"snapshot-slider\" min=\"0\" max=\""
      << times.size() - 1
      << "\" step=\"1\" value=\"0\" aria-label=\"snapshot time\"><output id=\"snapshot-time\">t = "
      << snapshot_time_label(times.front()) << " s</output></div>\n";
    for (std::size_t k = 0; k < times.size(); ++k) {
      const std::string label = snapshot_time_label(times[k]);
      h << "<div class=\"snapshot-frame\" data-t=\"" << label << "\" id=\"snapshot-" << label
        << "\"" << (k ? " hidden" : "") << ">\n";
      for (const FigureInfo& f : figures)
        if ((f.kind == "snapshot" || f.kind == "field" || f.kind == "surface" ||
             f.kind == "groups") &&
            snapshot_time_label(f.t_s) == label)
          h << image(figures_dir, f);
      h << "</div>\n";
    }
  }
  h << "</section>\n";

  if (has_lifetime_section(s)) {
    h << "<section id=\"lifetime\">\n<h2>Lifetime and faults</h2>\n" << lifetime_tables(s);
    for (const FigureInfo& f : figures)
      if (f.kind == "fault")
        h << "<figure id=\"figure-" << escape_html(f.stem) << "\">\n"
          << image(figures_dir, f) << "<figcaption>" << escape_html(f.caption)
          << "</figcaption>\n</figure>\n";
    h << "</section>\n";
  }

  // Interactive charts.
  const json specs = chart_specs(run.timeseries);
  h << "<section id=\"charts\">\n<h2>Time series (interactive)</h2>\n";
  if (chartjs) {
    h << "<p>Hover for values; click a legend entry to hide a series. " << chartjs->about
      << "</p>\n<div class=\"charts\">\n";
    for (const json& spec : specs)
      h << "<div class=\"chart-box\"><canvas id=\"" << spec["id"].get<std::string>()
        << "\"></canvas></div>\n";
    h << "</div>\n";
  } else {
    h << "<p class=\"note\" id=\"charts-unavailable\">Interactive charts are unavailable: "
      << why_no_charts << " The figures below show the same data.</p>\n";
  }
  h << "</section>\n";

  h << "<section id=\"figures\">\n<h2>Figures</h2>\n";
  bool any = false;
  for (const FigureInfo& f : figures) {
    if (f.kind == "snapshot" || f.kind == "field" || f.kind == "surface" || f.kind == "groups" ||
        f.kind == "fault")
      continue;
    any = true;
    h << "<figure id=\"figure-" << escape_html(f.stem) << "\">\n"
      << image(figures_dir, f) << "<figcaption>" << escape_html(f.caption) << " (figures/"
      << escape_html(f.stem) << ".png, .svg, .pdf)</figcaption>\n</figure>\n";
  }
  if (!any)
    h << "<p class=\"note\">Figures are off for this run (<code>output.figures: "
         "false</code>).</p>\n";
  h << "</section>\n";

  h << "<footer><pre id=\"page-errors\" hidden></pre></footer>\n";

  // Data for the slider and charts, then the library, then the code that uses both.
  json data;
  data["t"] = run.timeseries.has("t_s") ? run.timeseries.column("t_s") : std::vector<double>{};
  data["columns"] = json::object();
  for (const std::string& name : run.timeseries.names())
    data["columns"][name] = run.timeseries.column(name);
  data["charts"] = specs;
  h << "<script type=\"application/json\" id=\"timeseries-data\">"
    << escape_script(data.dump(-1, ' ', false, json::error_handler_t::replace)) << "</script>\n";
  if (chartjs) h << "<script>\n" << chartjs->code << "\n</script>\n";
  h << "<script>" << kReportScript << "</script>\n" << replay_scripts(run) << "</body>\n</html>\n";

  const fs::path path = run.dir / "report.html";
  write_file(path, h.str());
  return path;
}

fs::path render_run(const RunData& run, const RenderOptions& options) {
  const fs::path figures_dir = run.dir / "figures";
  std::vector<FigureInfo> figures;
  if (options.figures) figures = write_figures(run, figures_dir, options.figure);
  if (!options.report) return {};
  return fs::absolute(write_report(run, figures, figures_dir, options.page));
}

fs::path render_run_directory(const fs::path& dir, const RenderOptions& options) {
  return render_run(load_run_data(dir), options);
}

}  // namespace masnet::scenarios
