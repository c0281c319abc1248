#pragma once
// The static figures of a sweep's report (docs/sweeps.md, "Sensitivity figures"): for each
// metric with reference lines in the sweep file, the metric against a varied factor — mean over
// seeds with its 95 % interval, one series per combination of the other factors — with the
// lines across it, as sensitivity_<metric>.png, .svg and .pdf in the results folder.
#include <filesystem>
#include <string>
#include <vector>

#include "scenarios/report/plot/plot.hpp"
#include "scenarios/sweep/sweep_report.hpp"

namespace masnet::scenarios {

/// The plotting frame of a sensitivity figure, in pixels. Its y range is that of the means ±
/// their intervals and the reference values, widened by kSensitivityPad of its span each way.
inline constexpr plot::Box kSensitivityFrame{90, 60, 560, 420};
inline constexpr double kSensitivityPad = 0.08;

/// The stem of a metric's figure: "sensitivity_" and the metric's key as a column name
/// (pollution.final_over_peak -> sensitivity_pollution_final_over_peak).
std::string sensitivity_stem(const std::string& metric);

/// The reserved stroke colour of the reference lines: class "reference-line" in the SVG.
const std::vector<plot::SvgClass>& sensitivity_svg_classes();

/// Removes the sensitivity figures of earlier invocations from `dir`, then writes one figure
/// per metric that `in.reference_lines` names; returns them in the order of first mention.
/// Throws what write_figure throws.
std::vector<SweepFigure> write_sensitivity_figures(const SweepReportInput& in,
                                                   const std::filesystem::path& dir);

}  // namespace masnet::scenarios
