#include "scenarios/sweep/sweep_figures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <system_error>

#include <fmt/format.h>

#include "scenarios/output/output_file.hpp"
#include "scenarios/sweep/sweep.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using plot::Align;
using plot::Axes;
using plot::Marker;
using plot::Placement;
using plot::Rgb;
using plot::Style;

namespace {

// Reserved for the reference lines (see sensitivity_svg_classes); the legend sample uses a
// near neighbour so that it is not counted as a line.
constexpr Rgb kReferenceStroke{0.05, 0.05, 0.05};
constexpr Rgb kReferenceLegend{0.08, 0.08, 0.08};
constexpr double kRowPx = 16;
constexpr std::size_t kMaxLegendSeries = 40;

struct SeriesPoint {
  std::size_t point = 0;  // on the figure's axis
  MeanCi stats;
};

// The axes' names as legend entries show them: the last part of a dotted key when no other
// axis ends the same way.
std::vector<std::string> short_names(const std::vector<SweepReportAxis>& axes) {
  std::vector<std::string> names;
  for (const auto& a : axes)
    names.push_back(
        a.name.substr(a.name.rfind('.') == std::string::npos ? 0 : a.name.rfind('.') + 1));
  for (std::size_t i = 0; i < names.size(); ++i)
    if (std::count(names.begin(), names.end(), names[i]) > 1) names[i] = axes[i].name;
  return names;
}

std::string metric_title(const std::string& key) {
  for (const SweepReportMetric& m : sweep_report_metrics())
    if (key == m.key) return m.title;
  return key;
}

void draw_sensitivity(cairo_t* cr, const SweepReportInput& in, std::size_t a,
                      const std::string& metric,
                      const std::vector<const SweepReferenceLine*>& lines,
                      const std::map<std::vector<std::size_t>, std::vector<SeriesPoint>>& series,
                      const std::vector<std::string>& series_names, double width_px) {
  const SweepReportAxis& axis = in.axes[a];
  const std::string title = metric_title(metric);
  const bool numeric = axis.numeric && axis.x.size() == axis.labels.size();
  auto x_of = [&](std::size_t point) {
    return numeric ? axis.x[point] : static_cast<double>(point);
  };
  Axes axes(cr, kSensitivityFrame);
  double x_lo = -0.5, x_hi = static_cast<double>(axis.labels.size()) - 0.5;
  if (numeric) {
    const auto [lo, hi] = std::minmax_element(axis.x.begin(), axis.x.end());
    // Values spread over a decade or more (gains, rates) read better on a log axis.
    const bool log = *lo > 0 && *hi / *lo >= 10;
    const double f = log ? std::pow(*hi / *lo, 0.06) : 1.0,
                 d = *hi > *lo ? 0.06 * (*hi - *lo) : 1.0;
    x_lo = log ? *lo / f : *lo - d;
    x_hi = log ? *hi * f : *hi + d;
    axes.x_range(x_lo, x_hi, log ? plot::Scale::log : plot::Scale::linear);
  } else {
    axes.x_range(x_lo, x_hi);
    axes.set_categories(axis.labels);
  }
  std::vector<double> ys;
  for (const auto& [others, points] : series)
    for (const SeriesPoint& p : points) {
      const double ci = std::isfinite(p.stats.half_width) ? p.stats.half_width : 0.0;
      ys.push_back(p.stats.mean - ci);
      ys.push_back(p.stats.mean + ci);
    }
  for (const SweepReferenceLine* line : lines)
    ys.push_back(line->value);
  const auto [y_lo, y_hi] = plot::data_range({&ys}, kSensitivityPad);
  axes.y_range(y_lo, y_hi);
  axes.decorate(axis.name, title);

  Axes legend(cr, {kSensitivityFrame.x + kSensitivityFrame.w + 12, kSensitivityFrame.y - 8,
                   width_px - kSensitivityFrame.x - kSensitivityFrame.w - 22, 100});
  axes.clip();
  std::size_t k = 0;
  for (const auto& [others, points] : series) {
    const Style style{plot::categorical(k), 1.6, (k / 10) % 2 == 1};
    std::vector<double> xs, means;
    std::vector<plot::Point> marks;
    for (const SeriesPoint& p : points) {
      xs.push_back(x_of(p.point));
      means.push_back(p.stats.mean);
      marks.push_back({xs.back(), means.back()});
      if (std::isfinite(p.stats.half_width))
        axes.line({xs.back(), xs.back()},
                  {p.stats.mean - p.stats.half_width, p.stats.mean + p.stats.half_width},
                  Style{style.colour, 1.2});
    }
    if (numeric) axes.line(xs, means, style);
    axes.markers(marks, Marker::dot, 6, style.colour, style.colour);
    if (k < kMaxLegendSeries)
      legend.add_legend_entry(series_names[k].empty() ? title : series_names[k], style);
    ++k;
  }
  // Across the whole frame (the x range's ends), the label above its left end.
  for (const SweepReferenceLine* line : lines) {
    axes.line({x_lo, x_hi}, {line->value, line->value}, Style{kReferenceStroke, 1.8, true});
    plot::text(cr, axes.px(x_lo) + 6, axes.py(line->value) - 4, line->label, 11, Align::start,
               Align::end);
  }
  axes.unclip();
  for (const SweepReferenceLine* line : lines)
    legend.add_legend_entry(line->label, Style{kReferenceLegend, 1.8, true});
  if (series.size() > kMaxLegendSeries)
    legend.add_legend_entry(
        fmt::format("(+{} more series, not listed)", series.size() - kMaxLegendSeries),
        Style{{1, 1, 1}, 0.0});
  legend.legend(Placement::top_left);
  axes.title(title + " vs " + axis.name);
}

}  // namespace

std::string sensitivity_stem(const std::string& metric) {
  return "sensitivity_" + sanitize_column(metric);
}

const std::vector<plot::SvgClass>& sensitivity_svg_classes() {
  static const std::vector<plot::SvgClass> kClasses{{kReferenceStroke, "reference-line"}};
  return kClasses;
}

std::vector<SweepFigure> write_sensitivity_figures(const SweepReportInput& in,
                                                   const fs::path& dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if (name.rfind("sensitivity_", 0) == 0 && (ext == ".png" || ext == ".svg" || ext == ".pdf"))
      stale.push_back(entry.path());
  }
  for (const fs::path& p : stale)
    fs::remove(p, ec);

  std::vector<std::string> metrics;
  std::map<std::string, std::vector<const SweepReferenceLine*>> lines;
  for (const SweepReferenceLine& line : in.reference_lines) {
    if (!lines.count(line.metric)) metrics.push_back(line.metric);
    lines[line.metric].push_back(&line);
  }
  std::vector<SweepFigure> figures;
  for (const std::string& metric : metrics) {
    const auto& these = lines[metric];
    std::size_t a = in.axes.size();
    for (std::size_t i = 0; i < in.axes.size(); ++i)
      if (in.axes[i].name == these.front()->x) a = i;
    if (a == in.axes.size()) continue;
    // Each configuration's values over its seeds, then one series per other factors' points.
    std::map<std::vector<std::size_t>, std::vector<double>> samples;
    for (const SweepReportRun& r : in.runs) {
      const auto v = r.metrics.find(metric);
      if (r.ok && v != r.metrics.end() && r.points.size() == in.axes.size())
        samples[r.points].push_back(v->second);
    }
    std::map<std::vector<std::size_t>, std::vector<SeriesPoint>> series;
    for (const auto& [points, values] : samples) {
      std::vector<std::size_t> others = points;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(a));
      series[others].push_back({points[a], mean_ci95(values)});
    }
    for (auto& [others, points] : series)
      std::sort(points.begin(), points.end(),
                [](const SeriesPoint& p, const SeriesPoint& q) { return p.point < q.point; });
    // Legend entries: the other factors' values, e.g. "max_rate=2, boundary=no_flux".
    const std::vector<std::string> names = short_names(in.axes);
    std::vector<std::string> series_names;
    std::size_t longest = 0;
    for (const auto& [others, points] : series) {
      std::string name;
      for (std::size_t b = 0, j = 0; b < in.axes.size(); ++b) {
        if (b == a) continue;
        name += (name.empty() ? "" : ", ") + names[b] + "=" + in.axes[b].labels[others[j++]];
      }
      longest = std::max(longest, name.size());
      series_names.push_back(std::move(name));
    }
    for (const SweepReferenceLine* line : these)
      longest = std::max(longest, line->label.size());
    const double width = std::clamp(
        kSensitivityFrame.x + kSensitivityFrame.w + 60 + 6.4 * static_cast<double>(longest), 780.0,
        1400.0);
    const double rows =
        static_cast<double>(std::min(series.size(), kMaxLegendSeries + 1) + these.size());
    const double height = std::max(560.0, kSensitivityFrame.y + 20 + kRowPx * rows);
    const std::string stem = sensitivity_stem(metric);
    plot::write_figure(
        write_file, dir / stem, width, height,
        [&](cairo_t* cr) {
          draw_sensitivity(cr, in, a, metric, these, series, series_names, width);
        },
        sensitivity_svg_classes());
    std::string labels;
    for (const SweepReferenceLine* line : these)
      labels += (labels.empty() ? "" : "; ") + line->label;
    figures.push_back(
        {stem, fmt::format("{} against {}: the mean over seeds (bars: 95 % interval, where there "
                           "are several), one series per combination of the other factors; "
                           "dashed across: {}.",
                           metric_title(metric), in.axes[a].name, labels)});
  }
  return figures;
}

}  // namespace masnet::scenarios
