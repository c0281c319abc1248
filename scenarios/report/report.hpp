#pragma once
// report.html: one self-contained page per run directory (docs/outputs.md) that opens offline —
// metadata, the resolved scenario, summary tables, the figures inlined as data URIs, a time
// slider over the snapshots, and interactive time-series charts drawn by Chart.js, which is
// read from Debian's libjs-chart.js at render time and inlined (never committed). Sections:
// docs/outputs.md.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scenarios/report/figures.hpp"

namespace masnet::scenarios {

struct ReportOptions {
  /// The Chart.js UMD build to inline. Empty: $MASNET_CHARTJS, else the first of
  /// /usr/share/javascript/chart.js/{chart.umd.js, chart.min.js, chart.js} that exists.
  /// A missing or unusable file gives a report without interactive charts, saying so.
  std::filesystem::path chartjs;
};

/// The Chart.js file the report would inline, if any (see ReportOptions::chartjs).
std::optional<std::filesystem::path> find_chartjs(const ReportOptions& options);

/// Chart.js ready to inline in a <script> ("</script" escaped) and a line (HTML) on what it is.
struct ChartLibrary {
  std::string code;
  std::string about;
};
/// Loads the file find_chartjs names if it is a UMD build (what a plain <script> can run);
/// otherwise nothing, with the reason (HTML) in `why_not`.
std::optional<ChartLibrary> load_chartjs(const ReportOptions& options, std::string& why_not);

/// `dir`/`stem`.svg or .png, whichever is smaller, as a data URI for an <img>; empty when
/// neither exists.
std::string figure_data_uri(const std::filesystem::path& dir, const std::string& stem);

/// Text made safe for HTML content and attribute values (& < > ").
std::string escape_html(std::string_view text);

/// Writes `run.dir`/report.html from the run's data and the figures already written in
/// `figures_dir` (none listed: the report says figures are off). Returns the file's path.
std::filesystem::path write_report(const RunData& run, const std::vector<FigureInfo>& figures,
                                   const std::filesystem::path& figures_dir,
                                   const ReportOptions& options = {});

struct RenderOptions {
  bool figures = true;  ///< write figures/
  bool report = true;   ///< write report.html
  FigureOptions figure;
  ReportOptions page;
};

/// Writes the figures and report of a run read with load_run_data into `run.dir`. Returns the
/// report's absolute path, or an empty path when the report is off.
std::filesystem::path render_run(const RunData& run, const RenderOptions& options = {});

/// load_run_data + render_run (`masnet render`, and the end of `masnet run`). Throws
/// std::runtime_error when the directory's data cannot be read or the output written.
std::filesystem::path render_run_directory(const std::filesystem::path& dir,
                                           const RenderOptions& options = {});

}  // namespace masnet::scenarios
