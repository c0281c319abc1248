#include "scenarios/report/replay_section.hpp"

#include <fmt/format.h>

#include "scenarios/report/report.hpp"
#include "scenarios/report/web_assets.hpp"

namespace masnet::scenarios {
using nlohmann::json;

namespace {

// JSON placed inside <script type="application/json">: '<' only occurs inside JSON strings,
// where \u003c means the same, and without it no "</script" or "<!--" can end the element.
std::string json_for_script(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

constexpr std::string_view kStyle = R"(
.replay { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.replay canvas { border: 1px solid #ddd; }
.replay-panel { flex: 1; min-width: 260px; }
.replay-controls { display: flex; flex-wrap: wrap; align-items: center; gap: 0.6em; margin: 0.3em 0; }
.replay-controls input[type=range] { flex: 1; min-width: 180px; }
.replay-controls button { min-width: 5em; }
.replay-toggles label { display: block; margin: 0.2em 0; }
#replay-time { font-variant-numeric: tabular-nums; }
#replay-metrics { color: #444; font-size: 0.92em; }
)";

}  // namespace

bool has_replay_section(const RunData& run) {
  return run.replay.is_object() && run.replay.contains("frames") &&
         run.replay["frames"].is_array() && !run.replay["frames"].empty();
}

std::string replay_section(const RunData& run) {
  if (!has_replay_section(run)) return {};
  const json& frames = run.replay["frames"];
  std::string speeds;
  for (const char* speed : {"0.25", "0.5", "1", "2", "4", "8"})
    speeds += fmt::format("<option value=\"{}\"{}>{}×</option>", speed,
                          std::string_view(speed) == "1" ? " selected" : "", speed);
  std::string toggles;
  for (const auto& [key, label] : {std::pair{"raster", "density raster"},
                                   {"cells", "cells as the robots computed them"},
                                   {"oracle", "oracle cells (dashed)"},
                                   {"trails", "trails"},
                                   {"flashes", "transmissions (rings)"}})
    toggles += fmt::format("<label><input type=\"checkbox\" id=\"replay-{}\" checked> {}</label>\n",
                           key, label);
  return fmt::format(
      "<section id=\"replay\">\n<h2>Replay</h2>\n"
      "<p>The run as it happened, from <code>replay.json</code>: {} frames, one every {} s of "
      "simulated time. Each robot (disc) with its trail and its cell as it computed it (solid), "
      "the oracle's cell (dashed), the targets or sources (red), the density on a square-root "
      "colour scale, and a ring around each robot that transmitted since the previous "
      "frame.</p>\n"
      "<div class=\"replay\">\n<canvas id=\"replay-canvas\" width=\"640\" height=\"640\">"
      "</canvas>\n<div class=\"replay-panel\">\n<div class=\"replay-controls\">"
      "<button type=\"button\" id=\"replay-play\" aria-pressed=\"false\">Play</button>"
      "<label>speed <select id=\"replay-speed\">{}</select></label></div>\n"
      "<div class=\"replay-controls\"><input type=\"range\" id=\"replay-scrubber\" min=\"0\" "
      "max=\"{}\" step=\"1\" value=\"0\" aria-label=\"replay frame\"></div>\n"
      "<output id=\"replay-time\">t = {} s</output>\n<p id=\"replay-metrics\"></p>\n"
      "<div class=\"replay-toggles\">\n{}</div>\n</div>\n</div>\n"
      "<script type=\"application/json\" id=\"replay-data\">{}</script>\n</section>\n",
      frames.size(),
      frames.size() > 1
          ? fmt::format("{:.4g}", frames[1].value("t", 0.0) - frames[0].value("t", 0.0))
          : std::string("—"),
      speeds, frames.size() - 1, fmt::format("{:.2f}", frames[0].value("t", 0.0)), toggles,
      json_for_script(run.replay));
}

std::string replay_scripts(const RunData& run) {
  if (!has_replay_section(run)) return {};
  return fmt::format("<script>\n{}</script>\n<script>\n{}</script>\n", scene_view_js(),
                     replay_player_js());
}

std::string_view replay_style() {
  return kStyle;
}

}  // namespace masnet::scenarios
