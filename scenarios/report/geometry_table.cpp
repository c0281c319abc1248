#include "scenarios/report/geometry_table.hpp"

#include <fmt/format.h>

namespace masnet::scenarios {
using nlohmann::json;

namespace {

// A number of the summary, "—" when absent or null.
std::string number(const json& j, const char* key, const char* format) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return "—";
  return fmt::format(fmt::runtime(format), j[key].get<double>());
}

std::string row(const std::string& what, const std::string& total, const std::string& each) {
  return fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                     what, total, each);
}

}  // namespace

std::string computation_table(const json& summary) {
  if (!summary.contains("protocol") || !summary["protocol"].contains("geometry"))
    return "<p>No computation counts.</p>\n";
  const json& p = summary["protocol"];
  const json& g = p["geometry"];
  std::string out =
      "<table id=\"computation-load\"><thead><tr><th>work</th><th class=\"num\">run "
      "total</th><th class=\"num\">per update</th></tr></thead><tbody>\n";
  out += row("half-plane clips (robots)", number(g, "half_plane_clips", "{:.0f}"),
             number(g, "clips_per_update", "{:.4g}"));
  out += row("point-in-cell tests (robots)", number(g, "point_in_cell_tests", "{:.0f}"),
             number(g, "point_tests_per_update", "{:.4g}"));
  out += row("point-in-cell tests (sensors answering SENSE)",
             number(g, "sensor_point_tests", "{:.0f}"),
             number(g, "sensor_point_tests_per_update", "{:.4g}"));
  // Messages attributed to updates, by type, summed: what the clips and tests stand beside.
  double per_update = 0.0;
  bool any = false;
  if (p.contains("messages_per_update") && p["messages_per_update"].is_object())
    for (const auto& [type, value] : p["messages_per_update"].items())
      if (value.is_number()) {
        per_update += value.get<double>();
        any = true;
      }
  const double updates = p.value("updates", 0.0);
  out += row("messages of the updates (sent and received by their robot)",
             any ? fmt::format("{:.0f}", per_update * updates) : "0",
             any ? fmt::format("{:.4g}", per_update) : "0");
  const json energy = summary.value("energy_j", json());
  out +=
      row("radio energy, J (tx + rx)",
          energy.is_object() && energy.contains("radio_tx") && energy.contains("radio_rx")
              ? fmt::format("{:.4g}", energy.value("radio_tx", 0.0) + energy.value("radio_rx", 0.0))
              : "—",
          number(energy, "per_update", "{:.4g}"));
  return out + "</tbody></table>\n";
}

}  // namespace masnet::scenarios
