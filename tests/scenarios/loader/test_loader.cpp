// The scenario loader against bad input (docs/scenario-reference.md): every file under malformed/
// is checked with `masnet validate` and `masnet run` as a subprocess, for its exact `file:line:col:
// message` lines, exit code 2 and no run directory; overrides, seeds and resolved defaults
// in-process.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "loader_helpers.hpp"
#include "scenarios/loader/scenario.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios;

namespace {

const std::string kMasnet = MASNET_BINARY_DIR "/scenarios/masnet";
const std::string kMalformed = MASNET_SOURCE_DIR "/tests/scenarios/malformed";
const std::string kExamples = MASNET_SOURCE_DIR "/scenarios";

// One malformed file and the exact lines `masnet validate` prints for it, run from its folder.
struct Case {
  const char* file;
  std::vector<std::string> lines;
};

const std::vector<Case> kCases = {
    {"yaml_syntax_error.yaml",
     {"yaml_syntax_error.yaml:6:1: YAML syntax error: end of sequence flow not found"}},
    {"yaml_tab_indentation.yaml",
     {"yaml_tab_indentation.yaml:3:6: YAML syntax error: illegal map value"}},
    {"empty.yaml",
     {"empty.yaml:1:1: the scenario is empty (expected a mapping with at least 'duration')"}},
    {"top_level_list.yaml",
     {"top_level_list.yaml:1:1: the scenario must be a mapping of sections (name, duration, "
      "sensors, ...)"}},
    {"unknown_top_level_key.yaml",
     {"unknown_top_level_key.yaml:3:1: unknown key 'sensor' (did you mean 'sensors'?)"}},
    {"unknown_nested_key.yaml",
     {"unknown_nested_key.yaml:4:3: unknown key 'los' in 'radio' (did you mean 'loss'?)"}},
    {"duplicate_key.yaml",
     {"duplicate_key.yaml:5:3: duplicate key 'loss' in 'radio' (first given on line 3)"}},
    {"text_for_number.yaml",
     {"text_for_number.yaml:3:14: radio.max_range: expected a number, got 'far'"}},
    {"text_for_section.yaml",
     {"text_for_section.yaml:2:8: radio: expected a mapping of keys, got 'fast'"}},
    {"mapping_for_list.yaml",
     {"mapping_for_list.yaml:4:14: robots.positions: expected a list of points [[x, y], ...], "
      "got a mapping"}},
    {"wrong_boolean.yaml",
     {"wrong_boolean.yaml:3:12: output.figures: expected true or false, got 'maybe'"}},
    {"fraction_for_integer.yaml",
     {"fraction_for_integer.yaml:4:7: sensors.nx: expected a whole number, got '40.5'"}},
    {"negative_count.yaml",
     {"negative_count.yaml:4:10: sensors.count: must be between 0 and 100000000 (got -5)"}},
    {"negative_seed.yaml",
     {"negative_seed.yaml:1:7: seed: must be between 0 and 9223372036854775807 (got -1)"}},
    {"zero_duration.yaml", {"zero_duration.yaml:2:11: duration: must be > 0 (got 0)"}},
    {"negative_duration.yaml", {"negative_duration.yaml:1:11: duration: must be > 0 (got -2.5)"}},
    // Only the missing key: the snapshots are not checked against a made-up duration.
    {"missing_duration.yaml",
     {"missing_duration.yaml:1:1: duration: missing required key 'duration' (seconds of "
      "simulated time)"}},
    {"loss_out_of_range.yaml",
     {"loss_out_of_range.yaml:3:9: radio.loss: must be in [0, 1) (got 1.0)"}},
    {"alpha_not_positive.yaml", {"alpha_not_positive.yaml:4:10: field.alpha: must be > 0 (got 0)"}},
    {"message_size_too_large.yaml",
     {"message_size_too_large.yaml:3:19: radio.sizes.header: must be between 0 and 65535 (got "
      "70000)"}},
    {"non_convex_domain.yaml",
     {"non_convex_domain.yaml:3:12: domain.polygon: the polygon is not convex (the domain must "
      "be a convex polygon)"}},
    {"self_intersecting_domain.yaml",
     {"self_intersecting_domain.yaml:3:12: domain.polygon: the polygon intersects itself"}},
    {"bad_rectangle.yaml",
     {"bad_rectangle.yaml:3:14: domain.rectangle: expected [xmin, ymin, xmax, ymax] with xmin < "
      "xmax and ymin < ymax"}},
    {"rectangle_and_polygon.yaml",
     {"rectangle_and_polygon.yaml:4:12: domain.polygon: give either 'rectangle' or 'polygon', "
      "not both"}},
    {"robot_outside_domain.yaml",
     {"robot_outside_domain.yaml:5:5: robots.positions: robot 1 at (1.5, 0.5) lies outside the "
      "domain"}},
    {"robot_grid_outside_domain.yaml",
     // Every robot outside is reported (up to ten).
     {"robot_grid_outside_domain.yaml:6:11: robots.layout: robot 2 of the 3 x 3 grid, at "
      "(0.833333, 0.166667), lies outside the domain (use layout positions or random)",
      "robot_grid_outside_domain.yaml:6:11: robots.layout: robot 5 of the 3 x 3 grid, at "
      "(0.833333, 0.5), lies outside the domain (use layout positions or random)",
      "robot_grid_outside_domain.yaml:6:11: robots.layout: robot 6 of the 3 x 3 grid, at "
      "(0.166667, 0.833333), lies outside the domain (use layout positions or random)",
      "robot_grid_outside_domain.yaml:6:11: robots.layout: robot 7 of the 3 x 3 grid, at "
      "(0.5, 0.833333), lies outside the domain (use layout positions or random)",
      "robot_grid_outside_domain.yaml:6:11: robots.layout: robot 8 of the 3 x 3 grid, at "
      "(0.833333, 0.833333), lies outside the domain (use layout positions or random)"}},
    {"positions_missing.yaml",
     {"positions_missing.yaml:3:3: robots.positions: layout positions needs 'positions: [[x, "
      "y], ...]'"}},
    {"bad_point.yaml",
     {"bad_point.yaml:4:27: robots.positions[1]: expected a point [x, y], got [1, 2, 3]"}},
    {"bad_enum.yaml",
     {"bad_enum.yaml:3:9: protocol.kind: expected one of none, radius_doubling, oracle, "
      "fixed_radius, gabriel, got 'radius_doublng' (did you mean 'radius_doubling'?)"}},
    {"key_for_other_layout.yaml",
     {"key_for_other_layout.yaml:5:7: sensors.nx: 'nx' applies to layout grid"}},
    {"scaling_key_for_other_kind.yaml",
     {"scaling_key_for_other_kind.yaml:4:10: density_scaling.gamma: 'gamma' applies to kind "
      "power"}},
    {"acoustic_without_targets.yaml",
     {"acoustic_without_targets.yaml:3:3: field.targets: an acoustic field needs at least one "
      "target"}},
    {"target_start_and_waypoints.yaml",
     {"target_start_and_waypoints.yaml:5:14: field.targets[0].start: give either 'start' (with "
      "'velocity') or 'waypoints', not both"}},
    {"gaussian_bump_bad_sigma.yaml",
     {"gaussian_bump_bad_sigma.yaml:5:35: field.bumps[0].sigma: must be > 0 (got 0)"}},
    {"diffusion_unstable_step.yaml",
     {"diffusion_unstable_step.yaml:4:56: field.diffusion.dt: dt_s = 0.01 exceeds 0.000387909 s, "
      "the stability "
      "limit of the single RK4 step that fidelity mode takes; use a smaller dt_s, fewer cells or "
      "mode physical "
      "(which substeps)"}},
    {"control_without_diffusion.yaml",
     {"control_without_diffusion.yaml:5:15: control.dispensers: the control section applies to "
      "field kind diffusion"}},
    {"log_distance_airtime.yaml",
     {"log_distance_airtime.yaml:4:24: radio.propagation.model: model 'log_distance' needs "
      "radio.level collision or csma"}},
    {"states_energy_keys.yaml",
     {"states_energy_keys.yaml:5:40: radio.energy.electronics: 'electronics' applies to model "
      "first_order",
      "states_energy_keys.yaml:5:59: radio.energy.tx_currents: no level reaches "
      "radio.propagation.tx_power 3 dBm"}},
    {"csma_knob_at_collision.yaml",
     {"csma_knob_at_collision.yaml:4:11: radio.jitter: 'jitter' applies to levels ideal and "
      "airtime (under contention, frames take the time the medium gives them; a sensor's reply "
      "jitter is protocol.reply_jitter)",
      "csma_knob_at_collision.yaml:5:9: radio.csma: 'csma' applies to level csma"}},
    {"snapshot_after_end.yaml",
     {"snapshot_after_end.yaml:3:23: output.snapshots[2]: must be in [0, 5] (got 7)"}},
    {"top_level_groups.yaml",
     {"top_level_groups.yaml:3:3: groups: robot groups are set under robots.groups "
      "(docs/formations.md)"}},
    {"groups_offsets_count.yaml",
     {"groups_offsets_count.yaml:3:46: robots.groups.offsets: shape offsets needs one offset per "
      "follower: size - 1 = 2, got 1"}},
    {"groups_bad_keys.yaml",
     {"groups_bad_keys.yaml:6:14: robots.groups.offsets: 'offsets' applies to shape offsets",
      "groups_bad_keys.yaml:7:14: robots.groups.spacing: must be > 0 (got 0)"}},
    // Errors in a sensor file are located in that file.
    {"sensor_csv_bad_line.yaml",
     {"sensors_bad_line.csv:4:5: expected a number, got 'zero' (lines are 'x,y' or "
      "'x,y,area')"}},
    {"sensor_csv_outside_domain.yaml",
     {"sensors_outside.csv:4:1: sensor 2 at (0.25, 1.25) lies outside the domain"}},
    {"sensor_csv_missing.yaml",
     {"sensor_csv_missing.yaml:4:9: sensors.file: cannot read sensor file "
      "'no_such_sensors.csv' (No such file or directory)"}},
    // Hostile input: nulls, bytes, names, YAML features, and values whose consequences would
    // not fit (docs/scenario-reference.md, "Limits").
    {"null_duration.yaml",
     {"null_duration.yaml:2:1: duration: expected a number, got nothing (null)"}},
    {"null_values.yaml",
     {"null_values.yaml:4:3: protocol.kind: expected one of none, radius_doubling, oracle, "
      "fixed_radius, gabriel, got nothing (null)",
      "null_values.yaml:5:1: radio: expected a mapping of keys, got nothing (null)",
      "null_values.yaml:8:3: robots.positions: expected a list of points [[x, y], ...], got "
      "nothing (null)",
      "null_values.yaml:10:3: output.snapshots: expected a list of numbers, got nothing (null)"}},
    {"invalid_utf8.yaml",
     {"invalid_utf8.yaml:3:10: the text is not valid UTF-8 (byte 0xB1 here); save the file as "
      "UTF-8"}},
    {"name_with_path.yaml",
     {"name_with_path.yaml:3:7: name: '../../x' is not a valid name (it names the run directory: "
      "use 1 to 64 of the characters A-Z a-z 0-9 . _ -, not starting with '.' or '-')"}},
    {"name_with_control_characters.yaml",
     {"name_with_control_characters.yaml:3:7: name: 'a\\x09b\\x1B[31m' is not a valid name (it "
      "names the run directory: use 1 to 64 of the characters A-Z a-z 0-9 . _ -, not starting with "
      "'.' or '-')"}},
    {"second_document.yaml",
     {"second_document.yaml:2:1: a second YAML document starts here (the file must hold a single "
      "document; remove the '---' and what follows)"}},
    {"yaml_tags.yaml",
     {"yaml_tags.yaml:1:11: YAML tags are not supported (got '!!str'); write the value alone, "
      "quoted if it must stay a text",
      "yaml_tags.yaml:3:10: YAML tags are not supported (got '!foo'); write the value alone, "
      "quoted if it must stay a text"}},
    {"alias_bomb.yaml",
     {"alias_bomb.yaml:7:45: the aliases (*name) repeat more than 100000 nodes in all "
      "(docs/scenario-reference.md, \"Limits\")"}},
    {"long_value.yaml",
     {"long_value.yaml:4:10: radio.level: expected one of ideal, airtime, collision, csma, got "
      "'abababababababababababababababababababababababababababababababababababababababab… (1000000 "
      "bytes in all)'"}},
    {"period_below_resolution.yaml",
     {"period_below_resolution.yaml:4:11: protocol.period: must be >= 1e-09 (1 ns, the clock's "
      "resolution) (got 1e-300)",
      "period_below_resolution.yaml:6:18: output.sample_period: must be >= 1e-09 (1 ns, the "
      "clock's resolution) (got 1e-12)"}},
    {"periodic_work_budget.yaml",
     {"periodic_work_budget.yaml:5:11: beacons.period: the run would take about 9e+10 periodic "
      "steps (protocol updates 9e+03, beacons 9e+10, trajectory rows 4.5e+03, replay frames "
      "2.5e+03), more than the limit of 1e+09; use a longer period or a shorter duration, or set "
      "limits.allow_huge: true"}},
    {"duration_too_long.yaml",
     {"duration_too_long.yaml:2:11: duration: must be <= 1e+09 (got 1e10)"}},
    {"too_many_samples.yaml",
     {"too_many_samples.yaml:4:18: output.sample_period: the run would write about 1e+08 "
      "timeseries rows, more than the limit of 1e+07; use a longer sample_period, or set "
      "limits.allow_huge: true"}},
    {"velocity_too_large.yaml",
     {"velocity_too_large.yaml:6:37: field.bumps[0].velocity: coordinates must be within ±1e+12, "
      "got [1e308, 1e308]"}},
    {"number_too_large.yaml",
     {"number_too_large.yaml:3:14: radio.max_range: must be <= 1e+12 (got 1e300)"}},
    {"acoustic_density_overflow.yaml",
     {"acoustic_density_overflow.yaml:5:10: field.alpha: the density could reach 1e520 (amplitude "
      "over min_distance^alpha for acoustic fields), past the limit of 1e100; use a smaller "
      "amplitude or alpha, or a larger min_distance"}},
    {"scaled_density_overflow.yaml",
     {"scaled_density_overflow.yaml:8:10: density_scaling.gamma: the scaled density could reach "
      "1e120 (the peak density 1e6 to the power gamma), past the limit of 1e100; use a smaller "
      "gamma"}},
    {"sensor_grid_over_limit.yaml",
     {"sensor_grid_over_limit.yaml:5:7: sensors.ny: a 10000 x 10000 grid has more than 10000000 "
      "sensors (limits.allow_huge: true allows up to 100000000)"}},
    {"robot_grid_over_limit.yaml",
     {"robot_grid_over_limit.yaml:5:7: robots.ny: a 2000 x 1000 grid has more than 1000000 robots "
      "(limits.allow_huge: true allows up to 10000000)"}},
    {"many_robots_outside_domain.yaml",
     {"many_robots_outside_domain.yaml:5:14: robots.positions: robot 1 at (1.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 2 at (2.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 3 at (3.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 4 at (4.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 5 at (5.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 6 at (6.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 7 at (7.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 8 at (8.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 9 at (9.5, 0.5) lies outside "
      "the domain",
      "many_robots_outside_domain.yaml:5:14: robots.positions: robot 10 at (10.5, 0.5) lies "
      "outside the domain",
      "many_robots_outside_domain.yaml:5:14: ... and 3 more robots outside the domain"}},
    {"random_layout_sliver.yaml",
     {"random_layout_sliver.yaml:7:10: sensors.count: layout random would draw about 2e+08 points "
      "(the domain "
      "fills 0.05% of its bounding box), more than the limit of 2e+07; use fewer nodes, or set "
      "limits.allow_huge: true"}},
    {"bad_limits.yaml",
     {"bad_limits.yaml:3:15: limits.allow_huge: expected true or false, got 'yes please'"}},
    // Every problem is reported, in the order of the file.
    {"several_errors.yaml",
     {"several_errors.yaml:5:14: radio.max_range: must be > 0 (got -1)",
      "several_errors.yaml:8:9: protocol.kind: expected one of none, radius_doubling, oracle, "
      "fixed_radius, gabriel, got 'oracel' (did you mean 'oracle'?)",
      "several_errors.yaml:9:11: protocol.period: must be > 0 (got 0)",
      "several_errors.yaml:12:10: robots.count: must be between 1 and 10000000 (got 0)"}},
};

// The shell's single quotes around a path.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

using masnet::test::Outcome;
using masnet::test::shell;

// Only the standard error of `masnet ARGS`, run in `directory`.
Outcome masnet_stderr(const std::string& directory, const std::string& args) {
  return shell("cd " + quoted(directory) + " && " + quoted(kMasnet) + " " + args +
               " 2>&1 >/dev/null");
}

// The lines as printed for a scenario named `directory`/FILE: paths in the locations and in
// "cannot read sensor file '...'" then start with `directory`.
std::string joined(const std::vector<std::string>& lines, const std::string& directory = "") {
  std::string text;
  for (std::string line : lines) {
    const std::string quoted_file = "sensor file '";
    if (const auto at = line.find(quoted_file); !directory.empty() && at != std::string::npos)
      line.insert(at + quoted_file.size(), directory + "/");
    text += (directory.empty() ? "" : directory + "/") + line + "\n";
  }
  return text;
}

using masnet::test::texts;
using TempDir = masnet::test::TempDir;

}  // namespace

TEST_CASE("every malformed file has its expected messages in this test", "[scenarios]") {
  std::set<std::string> listed;
  for (const Case& c : kCases)
    listed.insert(c.file);
  std::set<std::string> present;
  for (const auto& entry : fs::directory_iterator(kMalformed))
    if (entry.path().extension() == ".yaml") present.insert(entry.path().filename().string());
  CHECK(listed == present);
  CHECK(listed.size() >= 20);
}

TEST_CASE("masnet validate reports each malformed file's exact located errors and exits 2",
          "[scenarios]") {
  REQUIRE(fs::exists(kMasnet));
  for (const Case& c : kCases) {
    INFO(c.file);
    const Outcome outcome = masnet_stderr(kMalformed, "validate " + quoted(c.file));
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.output == joined(c.lines));
  }
}

TEST_CASE("masnet run refuses each malformed file with exit 2 and creates no directory",
          "[scenarios]") {
  REQUIRE(fs::exists(kMasnet));
  for (const Case& c : kCases) {
    INFO(c.file);
    // Run from an empty directory, so that neither --out nor a default runs/ could hide.
    TempDir cwd;
    REQUIRE(!cwd.path.empty());
    const fs::path out = cwd.path / "out";
    const Outcome outcome =
        masnet_stderr(cwd.path.string(), "run " + quoted(kMalformed + "/" + c.file) + " --out " +
                                             quoted(out.string()) + " --quiet");
    CHECK(outcome.exit_code == 2);
    // The same messages, located in the file as named on the command line.
    CHECK(outcome.output == joined(c.lines, kMalformed));
    CHECK_FALSE(fs::exists(out));
    CHECK(fs::is_empty(cwd.path));
  }
}

TEST_CASE("masnet validate accepts the example scenarios with an ok line and exit 0",
          "[scenarios]") {
  const Outcome beacons = shell(quoted(kMasnet) + " validate " +
                                quoted(kExamples + "/examples/beacons.yaml") + " 2>/dev/null");
  CHECK(beacons.exit_code == 0);
  CHECK(beacons.output ==
        kExamples + "/examples/beacons.yaml: ok (400 sensors, 3 robots, 10.000 s)\n");
  const Outcome acoustic = shell(quoted(kMasnet) + " validate " +
                                 quoted(kExamples + "/paper/acoustic_tracking.yaml") + " 2>&1");
  CHECK(acoustic.exit_code == 0);
  CHECK(acoustic.output ==
        kExamples + "/paper/acoustic_tracking.yaml: ok (1600 sensors, 9 robots, 5.000 s)\n");
}

TEST_CASE("masnet validate locates a bad --set override on the command line", "[scenarios]") {
  const Outcome outcome = masnet_stderr(
      kExamples, "validate examples/beacons.yaml --set radio.loss=2 --set radio.los=0.2");
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.output ==
        "--set radio.loss=2: radio.loss: must be in [0, 1) (got 2)\n"
        "--set radio.los=0.2: unknown key 'los' in 'radio' (did you mean 'loss'?)\n");
  const Outcome fixed =
      masnet_stderr(kExamples, "validate examples/beacons.yaml --set radio.loss=0.3");
  CHECK(fixed.exit_code == 0);
  CHECK(fixed.output.empty());
}

TEST_CASE("both example scenarios load without diagnostics", "[scenarios]") {
  const LoadResult beacons = load_scenario(kExamples + "/examples/beacons.yaml", {});
  CHECK(texts(beacons.diagnostics).empty());
  REQUIRE(beacons.scenario);
  CHECK(beacons.scenario->name == "beacons");
  CHECK(beacons.scenario->world.sensors.size() == 400);
  CHECK(beacons.scenario->world.robots.size() == 3);
  CHECK(beacons.scenario->world.radio.loss == 0.1);

  const LoadResult acoustic = load_scenario(kExamples + "/paper/acoustic_tracking.yaml", {});
  CHECK(texts(acoustic.diagnostics).empty());
  REQUIRE(acoustic.scenario);
  const ScenarioDef& def = *acoustic.scenario;
  CHECK(def.duration_s == 5.0);
  CHECK(def.world.sensors.size() == 1600);
  CHECK(def.world.robots.size() == 9);
  CHECK(def.world.field.targets.size() == 2);
  // min_distance: auto is h/2 with h = 1/40 (docs/decisions/0002-acoustic-field.md).
  CHECK(def.world.field.min_distance == Approx(1.0 / 80.0));
  CHECK(def.resolved["field"]["min_distance"].get<double>() == Approx(1.0 / 80.0));
  CHECK(def.output.snapshots == std::vector<double>{0, 1, 2, 3, 4, 5});
}

TEST_CASE("the resolved scenario holds every default", "[scenarios]") {
  const LoadResult loaded = load_scenario_text("duration: 2\n", "inline.yaml", {});
  REQUIRE(texts(loaded.diagnostics).empty());
  REQUIRE(loaded.scenario);
  const nlohmann::json& r = loaded.scenario->resolved;
  CHECK(r["name"] == "inline");
  CHECK(r["seed"] == 1);
  CHECK(r["duration"] == 2.0);
  CHECK(r["domain"]["rectangle"] == nlohmann::json::array());
  CHECK(r["sensors"]["layout"] == "grid");
  CHECK(r["sensors"]["nx"] == 10);
  CHECK(r["sensors"]["alignment"] == "cell_centred");
  CHECK(r["field"]["kind"] == "uniform");
  CHECK(r["field"]["value"] == 1.0);
  CHECK(r["density_scaling"]["kind"] == "identity");
  CHECK(r["robots"]["layout"] == "grid");
  CHECK(r["robots"]["k"] == 3.0);
  CHECK(r["robots"]["k_v"] == 1.0);
  CHECK(r["radio"]["max_range"] == 1.5);
  CHECK(r["radio"]["level"] == "airtime");
  CHECK(r["radio"]["loss"] == 0.0);
  CHECK(r["radio"]["energy"]["electronics"] == 50e-9);
  CHECK(r["radio"]["sizes"]["header"] == 8);
  CHECK(r["protocol"]["kind"] == "radius_doubling");
  CHECK(r["protocol"]["growth"] == "to_2d");
  CHECK(r["protocol"]["decay"]["patience"] == 3);
  CHECK(r["beacons"]["senders"] == "none");
  CHECK(r["output"]["sample_period"] == 0.05);
  CHECK(r["output"]["report"] == true);
  // The defaults themselves: a 10 × 10 cell-centred grid and a 3 × 3 robot grid on the unit square.
  CHECK(loaded.scenario->world.sensors.size() == 100);
  CHECK(loaded.scenario->world.sensors.front().position.x() == Approx(0.05));
  CHECK(loaded.scenario->world.robots.size() == 9);
  CHECK(loaded.scenario->world.robots.front().x() == Approx(1.0 / 6.0));
}

TEST_CASE("a --set override changes its value and leaves the rest of the file alone",
          "[scenarios]") {
  const std::string text =
      "duration: 5\nradio:\n  max_range: 0.5\n  loss: 0.1\nprotocol:\n  kind: oracle\n";
  const LoadResult loaded =
      load_scenario_text(text, "inline.yaml",
                         {"radio.loss=0.25", "protocol.decay.patience=7", "output.figures=false"});
  REQUIRE(texts(loaded.diagnostics).empty());
  REQUIRE(loaded.scenario);
  const ScenarioDef& def = *loaded.scenario;
  CHECK(def.world.radio.loss == 0.25);
  CHECK(def.resolved["radio"]["loss"] == 0.25);
  // Sections and keys the override does not name keep their values from the file.
  CHECK(def.duration_s == 5.0);
  CHECK(def.world.radio.max_range == 0.5);
  CHECK(def.world.protocol.kind == "oracle");
  // An override may create the sections on its path (a key of another kind is still resolved).
  CHECK(def.resolved["protocol"]["decay"]["patience"] == 7);
  CHECK_FALSE(def.output.figures);
}

TEST_CASE("a bad --set override is located as --set KEY=VALUE", "[scenarios]") {
  const std::string text = "duration: 5\nradio:\n  loss: 0.1\n";
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"radio.loss=2"}).diagnostics) ==
        std::vector<std::string>{"--set radio.loss=2: radio.loss: must be in [0, 1) (got 2)"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"radio.lost=0.2"}).diagnostics) ==
        std::vector<std::string>{
            "--set radio.lost=0.2: unknown key 'lost' in 'radio' (did you mean 'loss'?)"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"groups.leader=0"}).diagnostics) ==
        std::vector<std::string>{"--set groups.leader=0: groups: robot groups are set under "
                                 "robots.groups (docs/formations.md)"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"duration.x=1"}).diagnostics) ==
        std::vector<std::string>{
            "--set duration.x=1: 'duration' is not a section, cannot set 'duration.x'"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"radio.loss"}).diagnostics) ==
        std::vector<std::string>{"--set radio.loss: expected KEY.PATH=VALUE"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"radio..loss=0"}).diagnostics) ==
        std::vector<std::string>{"--set radio..loss=0: empty key in 'radio..loss'"});
  CHECK(texts(load_scenario_text(text, "inline.yaml", {"radio.loss=[0"}).diagnostics) ==
        std::vector<std::string>{
            "--set radio.loss=[0: value is not valid YAML: end of sequence flow not found"});
  // A problem in the file is still located in the file.
  CHECK(texts(load_scenario_text("duration: 5\nradio:\n  loss: 3\n", "inline.yaml",
                                 {"radio.max_range=0.5"})
                  .diagnostics) ==
        std::vector<std::string>{"inline.yaml:3:9: radio.loss: must be in [0, 1) (got 3)"});
}

TEST_CASE("an empty file with overrides is a scenario made of the overrides", "[scenarios]") {
  const LoadResult loaded = load_scenario_text("", "inline.yaml", {"duration=3", "robots.nx=2"});
  REQUIRE(texts(loaded.diagnostics).empty());
  REQUIRE(loaded.scenario);
  CHECK(loaded.scenario->duration_s == 3.0);
  CHECK(loaded.scenario->world.robots.size() == 6);
}

TEST_CASE("the seed override replaces the file's seed and keys the random layouts", "[scenarios]") {
  const std::string text =
      "seed: 5\nduration: 1\nsensors: {layout: random, count: 50}\nrobots: {layout: random, "
      "count: 4}\n";
  const LoadResult from_file = load_scenario_text(text, "inline.yaml", {});
  const LoadResult overridden = load_scenario_text(text, "inline.yaml", {"seed=6"}, 42);
  const LoadResult again = load_scenario_text(text, "inline.yaml", {}, 42);
  REQUIRE(from_file.scenario);
  REQUIRE(overridden.scenario);
  REQUIRE(again.scenario);
  CHECK(from_file.scenario->seed == 5);
  // --seed is applied after --set seed=...
  CHECK(overridden.scenario->seed == 42);
  CHECK(overridden.scenario->world.seed == 42);
  CHECK(overridden.scenario->resolved["seed"] == 42);
  const auto& a = from_file.scenario->world;
  const auto& b = overridden.scenario->world;
  const auto& c = again.scenario->world;
  REQUIRE(a.sensors.size() == 50);
  REQUIRE(b.sensors.size() == 50);
  CHECK(a.sensors[0].position != b.sensors[0].position);
  CHECK(a.robots[0] != b.robots[0]);
  // Same seed, same layout.
  for (std::size_t i = 0; i < 50; ++i)
    CHECK(b.sensors[i].position == c.sensors[i].position);
  CHECK(b.robots == c.robots);
}

TEST_CASE("a sensor file is read relative to the scenario, with optional areas", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  {
    std::ofstream csv(dir.path / "sensors.csv");
    csv << "x,y,area\n0.25,0.25,0.5\n# a comment\n0.75,0.75\n";
  }
  const std::string text = "duration: 1\nsensors:\n  layout: file\n  file: sensors.csv\n";
  const LoadResult loaded = load_scenario_text(text, (dir.path / "s.yaml").string(), {});
  REQUIRE(texts(loaded.diagnostics).empty());
  REQUIRE(loaded.scenario);
  const auto& sensors = loaded.scenario->world.sensors;
  REQUIRE(sensors.size() == 2);
  CHECK(sensors[0].position == masnet::scenarios::Vec2{0.25, 0.25});
  CHECK(sensors[0].area == 0.5);
  // No area given: an equal share of Ω.
  CHECK(sensors[1].area == 0.5);
  CHECK(loaded.scenario->sensor_layout == "file");

  {
    std::ofstream csv(dir.path / "sensors.csv");
    csv << "0.25,0.25\n0.5,0.5,0.1,9\n0.75,0.75,-1\n";
  }
  const std::string csv_path = (dir.path / "sensors.csv").string();
  CHECK(texts(load_scenario_text(text, (dir.path / "s.yaml").string(), {}).diagnostics) ==
        std::vector<std::string>{csv_path + ":2:1: expected 2 or 3 columns (x,y[,area]), got 4",
                                 csv_path + ":3:1: the area (third column) must be > 0"});
}

TEST_CASE("a sensor grid too large to hold is refused before it is built", "[scenarios]") {
  CHECK(texts(load_scenario_text("duration: 1\nsensors:\n  nx: 100000\n  ny: 20000\n",
                                 "inline.yaml", {})
                  .diagnostics) ==
        std::vector<std::string>{"inline.yaml:4:7: sensors.ny: a 100000 x 20000 grid has more "
                                 "than 10000000 sensors (limits.allow_huge: true allows up to "
                                 "100000000)"});
  CHECK(texts(load_scenario_text("duration: 1\nsensors:\n  nx: 100000\n  ny: 20000\nlimits: "
                                 "{allow_huge: true}\n",
                                 "inline.yaml", {})
                  .diagnostics) ==
        std::vector<std::string>{
            "inline.yaml:4:7: sensors.ny: a 100000 x 20000 grid has more than 100000000 sensors"});
}
