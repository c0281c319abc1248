#pragma once
// The report's replay (docs/live-and-replay.md, "Replay in the report"): the frames of
// replay.json inlined as JSON and played on a canvas by scene_view.js, with play/pause, speed,
// a scrubber over the frames and toggles for the layers. Runs without replay.json get none.
#include <string>
#include <string_view>

#include "scenarios/report/run_data.hpp"

namespace masnet::scenarios {

/// Whether the run directory held a replay.json with at least one frame.
bool has_replay_section(const RunData& run);

/// <section id="replay">: the canvas, its controls and the frames (a <script
/// type="application/json" id="replay-data">); empty when has_replay_section is false.
std::string replay_section(const RunData& run);

/// The <script> elements that draw and play the section, for the end of <body>; empty when
/// has_replay_section is false.
std::string replay_scripts(const RunData& run);

/// The section's CSS, for the page's <style>.
std::string_view replay_style();

}  // namespace masnet::scenarios
