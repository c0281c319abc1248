#include "scenarios/report/web_assets.hpp"

#include "report_assets.hpp"

namespace masnet::scenarios {

std::string_view scene_view_js() {
  return assets::kSceneViewJs;
}

std::string_view replay_player_js() {
  return assets::kReplayPlayerJs;
}

std::string chart_js_source(const ReportOptions& options) {
  std::string why_not;
  std::optional<ChartLibrary> library = load_chartjs(options, why_not);
  return library ? std::move(library->code) : std::string();
}

}  // namespace masnet::scenarios
