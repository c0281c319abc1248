// A sweep file's `report`: reference lines that the report draws across a metric's figure.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "scenarios/sweep/sweep_parser.hpp"

namespace masnet::scenarios::sweep_parsing {

void SweepParser::read_report(const YAML::Node& node) {
  if (!node.IsDefined()) return;
  if (!node.IsMap()) {
    error(node, "report",
          "report: expected a mapping like {reference_lines: [{metric: "
          "pollution.final_over_peak, value: 0.36, label: \"the paper\"}]}");
    return;
  }
  std::vector<std::string> metrics;
  for (const SweepReportMetric& m : sweep_report_metrics())
    metrics.emplace_back(m.key);
  // The factors a metric can be drawn against: those with more than one value.
  std::vector<std::string> factors;
  for (const SweepAxis& axis : def_.axes)
    if (axis.points.size() > 1) factors.push_back(axis.name);
  std::string listed;
  for (const std::string& f : factors)
    listed += (listed.empty() ? "" : ", ") + f;

  Section report(reader_, node, "report", "/report");
  // The lines of one metric share its figure, so they share its x axis.
  std::map<std::string, std::pair<std::string, std::string>> x_of_metric;  // -> x, first line
  for (Section& line : report.sections("reference_lines")) {
    for (const char* key : {"metric", "value"})
      if (!line.has(key))
        line.error_at(key, std::string("missing (a reference line needs a metric and a value, e.g. "
                                       "{metric: pollution.final_over_peak, value: 0.36})"));
    SweepReferenceLine r;
    r.metric = line.choice_of("metric", metrics, "");
    r.value = line.number("value", 0.0);
    r.label = line.text("label", fmt::format("reference {:g}", r.value));
    r.x = line.text("x", factors.empty() ? std::string() : factors.front());
    if (factors.empty()) {
      line.error_at("x",
                    "this sweep varies nothing with more than one value, so there is no "
                    "parameter to draw the metric against");
    } else if (line.has("x") && std::find(factors.begin(), factors.end(), r.x) == factors.end()) {
      std::string message =
          "'" + shown_text(r.x) +
          "' is not a varied parameter with more than one value (varied: " + listed + ")";
      if (auto guess = closest(r.x, factors)) message += " (did you mean '" + *guess + "'?)";
      line.error_at("x", message);
    } else if (!r.metric.empty()) {
      const auto [first, inserted] = x_of_metric.emplace(r.metric, std::pair{r.x, line.path()});
      if (!inserted && first->second.first != r.x)
        line.error_at("x", "the lines of one metric share its figure and x axis: '" + r.x +
                               "' here, '" + first->second.first + "' in " + first->second.second);
    }
    line.finish();
    def_.reference_lines.push_back(std::move(r));
  }
  report.finish();
}

}  // namespace masnet::scenarios::sweep_parsing
