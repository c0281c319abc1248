#pragma once
// A curve of timeseries.csv summed up for summary.json: the total pollution with and without
// control (docs/outputs.md, `pollution`).
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/run/recorder.hpp"

namespace masnet::scenarios {

/// Peak, final, final/peak, whether the curve never rises after its peak, and the first time it
/// falls below the threshold after the peak (null if never); a threshold of 0 means 5 % of the
/// peak.
nlohmann::json curve_summary(const std::vector<Sample>& samples, double Sample::*value,
                             double threshold_or_zero);

}  // namespace masnet::scenarios
