#include "scenarios/report/fault_tables.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "scenarios/report/report.hpp"

namespace masnet::scenarios {
using nlohmann::json;

namespace {

// A number to six significant digits; null (never) as "never", missing as "—".
std::string value_text(const json& j, const char* null_text = "never") {
  if (j.is_null()) return null_text;
  if (j.is_number_integer() || j.is_number_unsigned()) return j.dump();
  if (j.is_number()) return fmt::format("{:.6g}", j.get<double>());
  if (j.is_boolean()) return j.get<bool>() ? "yes" : "no";
  if (j.is_string()) return escape_html(j.get<std::string>());
  return "—";
}

std::string at(const json& j, const char* key, const char* null_text = "never") {
  return j.contains(key) ? value_text(j[key], null_text) : "—";
}

}  // namespace

bool has_lifetime_section(const json& summary) {
  return summary.contains("lifetime") || summary.contains("recovery") || summary.contains("twin");
}

std::string lifetime_tables(const json& summary) {
  std::string out;
  if (summary.contains("lifetime") && summary["lifetime"].is_object()) {
    const json& l = summary["lifetime"];
    const json deaths = l.value("deaths", json::object());
    static const std::vector<std::pair<const char*, const char*>> kTimes{
        {"first_sensor_death_s", "first sensor down (s)"},
        {"sensors_dead_10pct_s", "10 % of the sensors down (s)"},
        {"sensors_dead_50pct_s", "50 % of the sensors down (s)"},
        {"first_robot_death_s", "first robot down (s)"}};
    out += "<h3>Lifetime</h3>\n<table class=\"kv\" id=\"lifetime-table\">\n";
    for (const auto& [key, label] : kTimes)
      out += fmt::format("<tr><th>{}</th><td class=\"num\">{}</td></tr>\n", label, at(l, key));
    out += fmt::format(
        "<tr><th>nodes down: battery, fault</th><td class=\"num\">{}, {}</td></tr>\n"
        "<tr><th>sensors down, robots down</th><td class=\"num\">{}, {}</td></tr>\n"
        "<tr><th>restarts</th><td class=\"num\">{}</td></tr>\n"
        "<tr><th>sensors, robots up at the end</th><td class=\"num\">{}, {}</td></tr>\n",
        at(deaths, "battery"), at(deaths, "fault"), at(deaths, "sensors"), at(deaths, "robots"),
        at(l, "restarts"), at(l, "sensors_alive_final"), at(l, "robots_alive_final"));
    out += "</table>\n";
  }
  if (summary.contains("recovery") && summary["recovery"].is_array()) {
    out +=
        "<h3>Recovery from each fault</h3>\n<table id=\"recovery-table\"><thead><tr><th>fault</th>"
        "<th>kind</th><th class=\"num\">strikes (s)</th><th class=\"num\">lifted (s)</th>"
        "<th class=\"num\">coverage within 5 % of the twin after (s)</th>"
        "<th class=\"num\">cell correctness above 0.95 after (s)</th></tr></thead><tbody>\n";
    for (const json& f : summary["recovery"]) {
      const bool struck = f.value("struck", true);
      out += fmt::format(
          "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
          "<td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
          at(f, "index"), at(f, "kind"), at(f, "at_s"), at(f, "until_s"),
          struck ? at(f, "coverage_recovery_s") : "not struck",
          struck ? at(f, "correctness_recovery_s") : "not struck");
    }
    out += "</tbody></table>\n";
  }
  if (summary.contains("twin") && summary["twin"].is_object()) {
    const json& t = summary["twin"];
    const json coverage = summary.value("coverage", json::object());
    const json tracking = summary.value("tracking", json::object());
    const json energy = summary.value("energy_j", json::object());
    const json protocol = summary.value("protocol", json::object());
    out +=
        "<h3>Beside the fault-free twin</h3>\n<table id=\"twin-table\"><thead><tr><th></th>"
        "<th class=\"num\">with faults</th><th class=\"num\">fault-free twin</th></tr></thead>"
        "<tbody>\n";
    auto row = [&](const char* label, const json& own, const char* own_key, const char* key) {
      out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>\n",
                         label, at(own, own_key, "—"), at(t, key, "—"));
    };
    row("coverage cost at the end", coverage, "final_cost", "coverage_final_cost");
    if (t.contains("tracking_mean_error") && !t["tracking_mean_error"].is_null())
      row("tracking error, mean", tracking, "mean_error", "tracking_mean_error");
    row("radio energy, total (J)", energy, "total", "energy_total_j");
    row("updates", protocol, "updates", "updates");
    out += fmt::format(
        "<tr><td>fingerprint</td><td><code>{}</code></td><td><code>{}</code></td></tr>\n",
        at(summary, "fingerprint", "—"), at(t, "fingerprint", "—"));
    out += "</tbody></table>\n";
  }
  return out;
}

}  // namespace masnet::scenarios
