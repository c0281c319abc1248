#pragma once
// The figures of a run directory (docs/outputs.md), drawn from its files alone — summary.json,
// timeseries.csv, trajectories.csv, updates.csv, nodes.csv, snapshots.json, sensors.csv — so
// that `masnet render` can restyle them without rerunning. What each figure shows:
// docs/outputs.md.
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "scenarios/report/plot/plot.hpp"
#include "scenarios/report/run_data.hpp"

namespace masnet::scenarios {

/// Switches of the snapshot figures (`masnet render --no-oracle-cells --radius-circles`).
struct FigureOptions {
  bool oracle_cells = true;     ///< the oracle's exact cells, dashed
  bool radius_circles = false;  ///< each robot's radius R_i as a circle
};

/// A figure written as figures/<stem>.png, figures/<stem>.svg and figures/<stem>.pdf.
struct FigureInfo {
  std::string stem;
  std::string kind;     ///< snapshot, field, surface, groups, trajectories, curve, map (the
                        ///< energy map of a run without faults or batteries) or fault
  std::string caption;  ///< one sentence for the report
  double t_s = std::numeric_limits<double>::quiet_NaN();  ///< snapshot, field, surface, groups
};

/// Replaces `figures_dir` with every figure the run's data allow, and lists them in a stable
/// order: snapshots (and field maps and surfaces) by time, trajectories, the curves, then the
/// energy map and the figures of faults. Maps take Ω's aspect ratio (docs/outputs.md, "Sizes").
std::vector<FigureInfo> write_figures(const RunData& run, const std::filesystem::path& figures_dir,
                                      const FigureOptions& options = {});

/// The time part of a snapshot figure's name: 2 → "2.0", 2.6 → "2.6", 0.125 → "0.125".
std::string snapshot_time_label(double t_s);

/// The reserved stroke colours that mark the robots' computed cells (class "cell") and the
/// oracle's cells (class "oracle-cell") in the snapshot SVGs.
const std::vector<plot::SvgClass>& snapshot_svg_classes();

}  // namespace masnet::scenarios
