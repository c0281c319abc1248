#pragma once
// report.html of a sweep (docs/sweeps.md): one self-contained page comparing configurations
// (combinations of the varied values) over seeds — mean and 95 % confidence interval (Student t)
// of messages, bytes, what contention did, energy, rounds, cell correctness, coverage, tracking
// and pollution figures — in a table sortable by clicking a header, and a chart of each metric
// against each varied parameter, drawn by Chart.js read from Debian's libjs-chart.js and inlined at
// render time (never committed). Without it the page has the tables and says why.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "scenarios/sweep/sweep_statistics.hpp"

namespace masnet::scenarios {

/// A horizontal line across a metric's sensitivity figure: `report.reference_lines` of a sweep
/// file (docs/sweeps.md), e.g. a value a paper reports.
struct SweepReferenceLine {
  std::string metric;  ///< a key of sweep_report_metrics()
  double value = 0;    ///< in the metric's units
  std::string label;   ///< written above the line; empty: "reference <value>"
  std::string x;       ///< the varied factor on the x axis (an axis name)
};

/// A figure written beside report.html (`<stem>`.png, .svg and .pdf) and embedded in it.
struct SweepFigure {
  std::string stem;
  std::string caption;
};

/// One factor of the sweep as the report shows it.
struct SweepReportAxis {
  std::string name;                 ///< "radio.loss", "variant", first key of a zip group
  std::vector<std::string> labels;  ///< one per point
  std::vector<double> x;            ///< numeric axes: the value of each point
  bool numeric = false;             ///< a linear x axis (else categories)
};

/// One run as stored in results.sqlite.
struct SweepReportRun {
  std::size_t index = 0;
  std::string id;
  std::uint64_t seed = 0;
  std::string label;
  std::vector<std::size_t> points;  ///< the point of each axis
  bool ok = false;
  std::string error;
  std::map<std::string, double> metrics;  ///< dotted summary keys (the `metrics` table)
};

struct SweepReportInput {
  std::string title;
  std::string sweep_file, base_file;
  std::size_t seeds = 0;       ///< seeds per configuration
  std::size_t total_runs = 0;  ///< runs in the expansion (some may be missing)
  std::vector<SweepReportAxis> axes;
  std::vector<SweepReportRun> runs;
  /// The Chart.js UMD build to inline; empty: the same search as a run's report
  /// ($MASNET_CHARTJS, then /usr/share/javascript/chart.js/).
  std::filesystem::path chartjs;
  std::vector<SweepReferenceLine> reference_lines;
  /// Figures already written in `figures_dir` (write_sensitivity_figures), embedded as images.
  std::vector<SweepFigure> figures;
  std::filesystem::path figures_dir;
};

/// A metric the report compares: its dotted summary key and a title with units.
struct SweepReportMetric {
  const char* key;
  const char* title;
};
/// The metrics compared, in table order; those absent from every run are left out.
const std::vector<SweepReportMetric>& sweep_report_metrics();

/// The whole page.
std::string render_sweep_report(const SweepReportInput& input);

}  // namespace masnet::scenarios
