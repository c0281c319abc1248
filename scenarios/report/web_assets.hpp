#pragma once
// The web code compiled into masnet, for the pages it writes and serves: the scene drawing
// (scene_view.js, the global MasnetScene: docs/live-and-replay.md) and Chart.js as the report
// inlines it. Both work offline: nothing is fetched when a page opens.
#include <string>
#include <string_view>

#include "scenarios/report/report.hpp"

namespace masnet::scenarios {

/// scenarios/report/assets/scene_view.js: plain JavaScript (ASCII, no "</"), ready to place in
/// a <script> element.
std::string_view scene_view_js();

/// scenarios/report/assets/replay_player.js: the report's replay controls (needs scene_view_js).
std::string_view replay_player_js();

/// Chart.js ready to place in a <script> element, from the file find_chartjs(options) names;
/// empty when there is none or it is not a UMD build (load_chartjs says why).
std::string chart_js_source(const ReportOptions& options = {});

}  // namespace masnet::scenarios
