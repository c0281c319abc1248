#include "scenarios/sweep/sweep_report.hpp"

#include <algorithm>
#include <ctime>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scenarios/report/report.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<SweepReportMetric>& sweep_report_metrics() {
  static const std::vector<SweepReportMetric> metrics = {
      {"messages.total.count", "messages sent"},
      {"messages.total.bytes", "bytes sent"},
      // Radio levels collision and csma only.
      {"messages.total.delivered", "receptions delivered"},
      {"messages.total.collided", "receptions lost to overlap"},
      {"messages.total.channel_lost", "receptions lost to the channel"},
      {"messages.total.dropped", "frames dropped"},
      {"messages.total.retries", "retries"},
      {"messages.total.backoffs", "backoffs"},
      {"messages.total.latency_mean_s", "delivery latency, mean (s)"},
      {"messages.total.latency_p99_s", "delivery latency, p99 (s)"},
      {"energy_j.total", "energy, total (J)"},
      {"energy_j.per_node_max", "energy, max per node (J)"},
      {"energy_per_update_j", "energy per update (J)"},
      {"protocol.rounds_mean", "rounds per update"},
      {"protocol.rounds_max", "rounds, max"},
      {"protocol.cell_correctness", "cell correctness (0..1)"},
      {"coverage.final_cost", "coverage cost, final"},
      {"tracking.mean_error", "tracking error, mean"},
      {"tracking.max_error_after_1s", "tracking error, max after 1 s"},
      {"pollution.peak", "pollution, peak"},
      {"pollution.final_over_peak", "pollution, final / peak"},
      {"pollution.time_to_clean_s", "time to clean (s)"},
      {"pollution.neutraliser_used", "neutraliser used"},
      {"pollution.baseline.final_over_peak", "no control: final / peak"},
  };
  return metrics;
}

namespace {

// Four significant digits, in fixed notation where that stays readable (50654, 45.70, 0.2408).
std::string number(double v) {
  if (!std::isfinite(v)) return "—";
  if (v == 0.0) return "0";
  const double magnitude = std::abs(v);
  if (magnitude < 1e-3 || magnitude >= 1e9) return fmt::format("{:.3e}", v);
  const int decimals = std::clamp(3 - static_cast<int>(std::floor(std::log10(magnitude))), 0, 6);
  return fmt::format("{:.{}f}", v, decimals);
}

// A JSON number for the page; NaN and infinities become null.
json finite(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

// The run report's Chart.js, with the advice that fits a sweep when it is missing.
std::optional<std::string> chart_library(const fs::path& requested, std::string& about) {
  ReportOptions options;
  options.chartjs = requested;
  if (!find_chartjs(options)) {
    about =
        "Charts need Chart.js, which was not found (looked for $MASNET_CHARTJS, then "
        "/usr/share/javascript/chart.js/chart.umd.js, chart.min.js, chart.js). Install Debian's "
        "<code>libjs-chart.js</code> and run the same <code>masnet sweep</code> command again: "
        "finished runs are skipped and this page is redrawn with charts.";
    return std::nullopt;
  }
  std::string why_not;
  std::optional<ChartLibrary> library = load_chartjs(options, why_not);
  if (!library) {
    about = why_not + " The page has tables only.";
    return std::nullopt;
  }
  about = library->about;
  return std::move(library->code);
}

struct Configuration {
  std::vector<std::size_t> points;
  std::size_t runs = 0, ok = 0;
  std::vector<MeanCi> stats;  // one per shown metric
};

constexpr const char* kStyle = R"(
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 1400px; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; }
th { background: #f0f0f0; cursor: pointer; user-select: none; position: sticky; top: 0; }
th[data-dir=asc]::after { content: " \25B2"; } th[data-dir=desc]::after { content: " \25BC"; }
td.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
.ci { color: #777; }
.note { background: #fff6d6; border: 1px solid #e6c200; padding: 0.5em 1em; }
.charts { display: flex; flex-wrap: wrap; gap: 1em; }
.chart { width: 420px; height: 300px; border: 1px solid #ddd; padding: 0.5em; }
pre { white-space: pre-wrap; margin: 0; font-size: 0.9em; }
dl { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; }
dt { font-weight: bold; } dd { margin: 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
)";

constexpr const char* kSortScript = R"(
document.querySelectorAll('table.sortable').forEach(function (table) {
  table.querySelectorAll('thead th').forEach(function (th, col) {
    th.addEventListener('click', function () {
      var asc = th.dataset.dir !== 'asc';
      table.querySelectorAll('thead th').forEach(function (h) { delete h.dataset.dir; });
      th.dataset.dir = asc ? 'asc' : 'desc';
      var body = table.tBodies[0], rows = Array.prototype.slice.call(body.rows);
      var key = function (row) {
        var cell = row.cells[col], v = cell.dataset.v;
        return v !== undefined && v !== '' ? parseFloat(v) : cell.textContent;
      };
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        var r = typeof x === 'number' && typeof y === 'number' ? x - y : String(x).localeCompare(String(y));
        return asc ? r : -r;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
)";

constexpr const char* kChartScript = R"(
(function () {
  // Error bars: a vertical segment mean ± CI at every point that has one.
  var errorBars = {
    id: 'errorBars',
    afterDatasetsDraw: function (chart) {
      var ctx = chart.ctx, y = chart.scales.y;
      chart.data.datasets.forEach(function (ds, i) {
        var meta = chart.getDatasetMeta(i);
        if (meta.hidden) return;
        ctx.save();
        ctx.strokeStyle = ds.borderColor;
        ctx.lineWidth = 1.2;
        meta.data.forEach(function (el, j) {
          var p = ds.data[j];
          if (!p || p.ci === null || p.ci === undefined || p.y === null) return;
          var top = y.getPixelForValue(p.y + p.ci), bottom = y.getPixelForValue(p.y - p.ci);
          ctx.beginPath();
          ctx.moveTo(el.x, top); ctx.lineTo(el.x, bottom);
          ctx.moveTo(el.x - 4, top); ctx.lineTo(el.x + 4, top);
          ctx.moveTo(el.x - 4, bottom); ctx.lineTo(el.x + 4, bottom);
          ctx.stroke();
        });
        ctx.restore();
      });
    }
  };
  var colors = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2',
                '#7f7f7f', '#bcbd22', '#17becf'];
  var fmt = function (v) { return v === null || v === undefined ? '—' : Number(v).toPrecision(4); };
  var made = 0;
  SWEEP_CHARTS.forEach(function (c) {
    var canvas = document.getElementById(c.id);
    if (!canvas) return;
    new Chart(canvas, {
      type: 'line',
      data: {
        labels: c.numeric ? undefined : c.labels,
        datasets: c.series.map(function (s, k) {
          return { label: s.name, data: s.points, borderColor: colors[k % colors.length],
                   backgroundColor: colors[k % colors.length], showLine: c.numeric, pointRadius: 4 };
        })
      },
      options: {
        animation: false, responsive: true, maintainAspectRatio: false,
        scales: {
          x: { type: c.numeric ? 'linear' : 'category', title: { display: true, text: c.xlabel } },
          y: { suggestedMin: c.ymin, suggestedMax: c.ymax, title: { display: true, text: c.ylabel } }
        },
        plugins: {
          title: { display: true, text: c.ylabel + ' vs ' + c.xlabel },
          legend: { display: c.series.length > 1 },
          tooltip: { callbacks: { label: function (item) {
            var p = item.raw;
            return item.dataset.label + ': ' + fmt(p.y) + ' ± ' + fmt(p.ci) + ' (n = ' + p.n + ')';
          } } }
        }
      },
      plugins: [errorBars]
    });
    ++made;
  });
  document.body.setAttribute('data-charts', String(made));
})();
)";

}  // namespace

std::string render_sweep_report(const SweepReportInput& in) {
  // Metrics shown: those some ok run has.
  std::vector<SweepReportMetric> metrics;
  for (const auto& m : sweep_report_metrics())
    if (std::any_of(in.runs.begin(), in.runs.end(),
                    [&](const SweepReportRun& r) { return r.ok && r.metrics.count(m.key); }))
      metrics.push_back(m);

  // Configurations in expansion order (points compare lexicographically, as they are expanded).
  std::map<std::vector<std::size_t>, Configuration> configs;
  std::map<std::vector<std::size_t>, std::vector<std::vector<double>>> samples;
  std::size_t ok = 0, failed = 0;
  for (const SweepReportRun& r : in.runs) {
    Configuration& c = configs[r.points];
    c.points = r.points;
    ++c.runs;
    auto& s = samples[r.points];
    s.resize(metrics.size());
    if (!r.ok) {
      ++failed;
      continue;
    }
    ++ok;
    ++c.ok;
    for (std::size_t m = 0; m < metrics.size(); ++m)
      if (auto v = r.metrics.find(metrics[m].key); v != r.metrics.end()) s[m].push_back(v->second);
  }
  for (auto& [points, c] : configs)
    for (const auto& values : samples[points])
      c.stats.push_back(mean_ci95(values));

  std::string about_charts;
  const std::optional<std::string> library = chart_library(in.chartjs, about_charts);

  std::string html;
  html.reserve(1 << 16);
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<title>masnet sweep: " + escape_html(in.title) + "</title>\n<style>" + kStyle +
          "</style>\n</head>\n<body>\n";
  html += "<h1>masnet sweep: " + escape_html(in.title) + "</h1>\n<dl>\n";
  html += "<dt>sweep file</dt><dd>" + escape_html(in.sweep_file) + "</dd>\n";
  html += "<dt>base scenario</dt><dd>" + escape_html(in.base_file) + "</dd>\n";
  std::string varied;
  for (const auto& a : in.axes)
    varied += (varied.empty() ? "" : " × ") + escape_html(a.name) + " (" +
              std::to_string(a.labels.size()) + ")";
  html += "<dt>varied</dt><dd>" + (varied.empty() ? std::string("nothing") : varied) + " × " +
          std::to_string(in.seeds) + " seeds</dd>\n";
  html += fmt::format(
      "<dt>runs</dt><dd id=\"run-counts\">{} in the sweep: {} ok, {} failed, {} not run</dd>\n",
      in.total_runs, ok, failed, in.total_runs - ok - failed);
  html += "<dt>masnet</dt><dd>" + escape_html(MASNET_VERSION) + "</dd>\n</dl>\n";
  html +=
      "<p>Every run's parameters and metrics: <code>results.csv</code> and "
      "<code>results.sqlite</code> "
      "in this folder (docs/sweeps.md).</p>\n";

  // The configuration table.
  html +=
      "<h2>Configurations</h2>\n<p>Mean ± half-width of the 95 % confidence interval of the mean "
      "over "
      "the ok runs (seeds) of each configuration, Student t with n − 1 degrees of freedom; no "
      "interval "
      "with one run. Click a header to sort.</p>\n";
  html += "<table class=\"sortable\" id=\"configurations\">\n<thead><tr><th>#</th>";
  for (const auto& a : in.axes)
    html += "<th>" + escape_html(a.name) + "</th>";
  html += "<th>runs ok</th>";
  for (const auto& m : metrics)
    html += "<th>" + escape_html(m.title) + "</th>";
  html += "</tr></thead>\n<tbody>\n";
  std::size_t row = 0;
  for (const auto& [points, c] : configs) {
    html += fmt::format("<tr><td class=\"num\" data-v=\"{}\">{}</td>", row, row + 1);
    ++row;
    for (std::size_t a = 0; a < in.axes.size() && a < points.size(); ++a) {
      const SweepReportAxis& axis = in.axes[a];
      const std::string label = points[a] < axis.labels.size() ? axis.labels[points[a]] : "?";
      if (axis.numeric && points[a] < axis.x.size())
        html += fmt::format("<td class=\"num\" data-v=\"{}\">{}</td>", axis.x[points[a]],
                            escape_html(label));
      else
        html += "<td>" + escape_html(label) + "</td>";
    }
    html += fmt::format("<td class=\"num\" data-v=\"{}\">{} / {}</td>", c.ok, c.ok, c.runs);
    for (const MeanCi& s : c.stats) {
      if (s.n == 0) {
        html += "<td class=\"num\" data-v=\"\">—</td>";
        continue;
      }
      html += fmt::format("<td class=\"num\" data-v=\"{}\">{}", s.mean, number(s.mean));
      if (std::isfinite(s.half_width))
        html += " <span class=\"ci\">± " + number(s.half_width) + "</span>";
      html += "</td>";
    }
    html += "</tr>\n";
  }
  html += "</tbody>\n</table>\n";

  // Charts: each metric against each axis with more than one point; one series per
  // combination of the other axes.
  json charts = json::array();
  std::string canvases;
  for (std::size_t a = 0; a < in.axes.size(); ++a) {
    const SweepReportAxis& axis = in.axes[a];
    if (axis.labels.size() < 2) continue;
    for (std::size_t m = 0; m < metrics.size(); ++m) {
      std::map<std::vector<std::size_t>, json> series;  // other axes' points -> points
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const auto& [points, c] : configs) {
        const MeanCi& s = c.stats[m];
        if (s.n == 0 || points.size() != in.axes.size()) continue;
        std::vector<std::size_t> others = points;
        others.erase(others.begin() + static_cast<std::ptrdiff_t>(a));
        json p = {{"y", s.mean}, {"ci", finite(s.half_width)}, {"n", s.n}};
        if (axis.numeric)
          p["x"] = axis.x[points[a]];
        else
          p["x"] = axis.labels[points[a]];
        series[others].push_back(p);
        const double w = std::isfinite(s.half_width) ? s.half_width : 0.0;
        lo = std::min(lo, s.mean - w);
        hi = std::max(hi, s.mean + w);
      }
      if (series.empty()) continue;
      json chart;
      const std::string id = fmt::format("chart-{}-{}", a, m);
      chart["id"] = id;
      chart["xlabel"] = axis.name;
      chart["ylabel"] = metrics[m].title;
      chart["numeric"] = axis.numeric;
      chart["labels"] = axis.labels;
      chart["ymin"] = finite(lo);
      chart["ymax"] = finite(hi);
      chart["series"] = json::array();
      for (const auto& [others, points] : series) {
        std::string name;
        for (std::size_t b = 0, k = 0; b < in.axes.size(); ++b) {
          if (b == a) continue;
          name += (name.empty() ? "" : ", ") + in.axes[b].name + "=" + in.axes[b].labels[others[k]];
          ++k;
        }
        chart["series"].push_back(
            {{"name", name.empty() ? std::string(metrics[m].title) : name}, {"points", points}});
      }
      charts.push_back(chart);
      canvases += "<div class=\"chart\"><canvas id=\"" + id + "\"></canvas></div>\n";
    }
  }
  html += "<h2>Charts</h2>\n";
  if (charts.empty()) {
    html += "<p>No charts: nothing is varied, or no run finished.</p>\n";
  } else if (!library) {
    html += "<p class=\"note\" id=\"no-charts\">" + about_charts + "</p>\n";
  } else {
    html +=
        "<p>Each metric against each varied parameter: mean and 95 % confidence interval over "
        "seeds; "
        "one series per combination of the other parameters. " +
        about_charts + "</p>\n";
    html += "<div class=\"charts\">\n" + canvases + "</div>\n";
  }

  // The static figures (metrics with reference lines), embedded like a run report's figures.
  if (!in.figures.empty()) {
    html += "<h2>Sensitivity figures</h2>\n";
    for (const SweepFigure& f : in.figures) {
      const std::string uri = figure_data_uri(in.figures_dir, f.stem);
      html += "<figure id=\"figure-" + escape_html(f.stem) + "\">\n";
      html += uri.empty() ? "<p class=\"note\">missing figure " + escape_html(f.stem) + "</p>\n"
                          : "<img src=\"" + uri + "\" alt=\"" + escape_html(f.caption) + "\">\n";
      html += "<figcaption>" + escape_html(f.caption) + " (" + escape_html(f.stem) +
              ".png, .svg, .pdf)</figcaption>\n</figure>\n";
    }
  }

  // Failed runs, with the loader's or the run's message.
  html += "<h2>Failed runs</h2>\n";
  if (failed == 0) {
    html += "<p>None.</p>\n";
  } else {
    html +=
        "<table class=\"sortable\" "
        "id=\"failed\"><thead><tr><th>run</th><th>id</th><th>parameters</th>"
        "<th>error</th></tr></thead>\n<tbody>\n";
    for (const SweepReportRun& r : in.runs)
      if (!r.ok)
        html += fmt::format(
            "<tr><td class=\"num\" "
            "data-v=\"{}\">{}</td><td><code>{}</code></td><td>{}</td><td><pre>{}</pre></td></tr>\n",
            r.index, r.index, escape_html(r.id), escape_html(r.label), escape_html(r.error));
    html += "</tbody>\n</table>\n";
  }

  html += std::string("<script>") + kSortScript + "</script>\n";
  if (library && !charts.empty()) {
    html += "<script>\n" + *library + "\n</script>\n";
    std::string data = charts.dump();
    for (std::size_t at = data.find("</"); at != std::string::npos; at = data.find("</", at))
      data.replace(at, 2, "<\\/");
    html += "<script>var SWEEP_CHARTS = " + data + ";\n" + kChartScript + "</script>\n";
  }
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace masnet::scenarios
