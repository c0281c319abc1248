#include "scenarios/run/run_warnings.hpp"

#include <fmt/format.h>

namespace masnet::scenarios {
namespace {

// Thresholds: well away from what a healthy run of the paper's scenarios shows (cell
// correctness 0.7-1, no truncated update), so that a warning always means something broke.
constexpr double kLowCorrectness = 0.5;
constexpr double kManyTruncated = 0.1;
constexpr double kManyWithoutMass = 0.25;

double number(const nlohmann::json& section, const char* key) {
  const auto it = section.find(key);
  return it != section.end() && it->is_number() ? it->get<double>() : 0.0;
}

}  // namespace

std::vector<std::string> run_warnings(const nlohmann::json& summary, double loss_probability) {
  std::vector<std::string> warnings;
  const nlohmann::json protocol = summary.value("protocol", nlohmann::json::object());
  const double updates = number(protocol, "updates");
  const std::string loss =
      loss_probability > 0 ? fmt::format(" (radio.loss is {:g})", loss_probability) : std::string();
  if (updates > 0) {
    const double correctness = number(protocol, "cell_correctness");
    // Without loss, a low figure with every heard cell right is robots moving during their
    // updates (the first instants of a run from a grid): no degradation. Loss, or cells wrong
    // even for what the robots heard, is.
    const double heard = protocol.contains("cell_correctness_heard")
                             ? number(protocol, "cell_correctness_heard")
                             : 0.0;
    if (correctness < kLowCorrectness && (loss_probability > 0 || heard < 0.9))
      warnings.push_back(
          fmt::format("only {:.1f} % of the updates built the robot's true Voronoi cell (cell "
                      "correctness {:.3f}){}: "
                      "the protocol's cells, costs and figures describe a degraded run",
                      100.0 * correctness, correctness, loss));
    const double truncated = number(protocol, "truncated");
    if (truncated > kManyTruncated * updates)
      warnings.push_back(
          fmt::format("{:.0f} of {:.0f} updates stopped at their radius cap (radio.max_range; "
                      "protocol.radius for "
                      "fixed_radius) before their cell was certain{}",
                      truncated, updates, loss));
    const double no_mass = number(protocol, "no_mass_updates");
    if (no_mass > kManyWithoutMass * updates)
      warnings.push_back(fmt::format(
          "{:.0f} of {:.0f} updates heard no sensor reading with mass: those robots did not move",
          no_mass, updates));
  } else if (protocol.value("name", std::string()) != "none" && protocol.contains("name")) {
    warnings.push_back("no robot completed a protocol update during the run");
  }
  // Nodes a scripted fault took down are the scenario's doing, not a surprise: only batteries.
  const nlohmann::json energy = summary.value("energy_j", nlohmann::json::object());
  const nlohmann::json deaths =
      summary.value("lifetime", nlohmann::json::object()).value("deaths", nlohmann::json::object());
  const double dead =
      deaths.contains("battery") ? number(deaths, "battery") : number(energy, "nodes_dead");
  if (dead > 0)
    warnings.push_back(
        fmt::format("{:.0f} node{} ran out of battery during the run", dead, dead == 1 ? "" : "s"));
  return warnings;
}

}  // namespace masnet::scenarios
