#pragma once
// A scenario file turned into definitions: the loader fills the definition
// structs of the lower layers, reports every bad value as `file:line:col: message`, and
// records the resolved scenario (defaults included) for summary.json. Every key is
// documented in docs/scenario-reference.md.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"
#include "scenarios/loader/reader.hpp"

namespace masnet::scenarios {

struct OutputDef {
  double sample_period_s = 0.05;      ///< timeseries.csv rows
  double trajectory_period_s = 0.02;  ///< trajectories.csv rows
  std::vector<double> snapshots;      ///< times of the snapshot figures, seconds
  bool updates = true;                ///< write updates.csv (one row per protocol update)
  bool figures = true;                ///< write figures/ (PNG, SVG and PDF)
  bool report = true;                 ///< write report.html
  /// replay.json (the report's animated replay): a frame every replay_period_s seconds, by
  /// default the larger of trajectory_period_s and duration / 250 (docs/live-and-replay.md).
  bool replay = true;
  double replay_period_s = 0.0;
  /// Acoustic runs: a robot is in a target's group within this distance of it, world units;
  /// 0 = √(area / (π · robots)), derived by the recorder (docs/outputs.md, "Tracking").
  double tracking_radius = 0.0;
};

struct ScenarioDef {
  std::string name;
  std::string source_path;
  std::uint64_t seed = 1;
  double duration_s = 0.0;
  agents::WorldDef world;
  OutputDef output;
  std::string sensor_layout;  ///< "grid", "random" or "file": said in the report
  /// The number of sensors, also when LoadOptions::build_sensors left world.sensors empty.
  std::size_t sensor_count = 0;
  /// Diffusion runs: also run the same scenario and seed with the dispensers off and report both.
  bool baseline = false;
  /// Pollution counts as cleaned when Σ readings falls below this; 0 = 5 % of the peak.
  double clean_threshold = 0.0;
  /// Events of one instant in the kernel's origin order instead of the scheduling order
  /// (docs/time-and-ordering.md): `tie_order: origin`.
  bool ties_by_origin = false;
  nlohmann::json resolved;  ///< every key with its value, defaults included
};

/// How much the loader builds.
struct LoadOptions {
  /// Build the sensor list. `masnet validate` only counts the sensors (a 10^4 × 10^4 grid is
  /// 2.4 GB); a sensor file is read either way, its sensors checked against the domain.
  bool build_sensors = true;
  /// Honour `limits.allow_huge`. A fuzzer turns this off so that no input can raise the
  /// limits of docs/scenario-reference.md.
  bool allow_huge = true;
};

struct LoadResult {
  std::optional<ScenarioDef> scenario;  ///< set when there is no diagnostic
  std::vector<Diagnostic> diagnostics;
  /// Problems that do not stop the run (a protocol knob of another kind), located.
  std::vector<Diagnostic> warnings;
  /// The dotted path of every key the loader knows for this scenario's kinds ("[]" for list
  /// items): what docs/scenario-reference.md must document.
  std::set<std::string> known_keys;
};

/// Loads `path` (a regular file of at most 16 MiB), applying `overrides` ("a.b.c=VALUE", VALUE
/// parsed as YAML) and then the seed override. Never throws for bad input: problems come back as
/// diagnostics.
LoadResult load_scenario(const std::string& path, const std::vector<std::string>& overrides,
                         std::optional<std::uint64_t> seed = std::nullopt,
                         const LoadOptions& options = {});

/// The same from YAML text (tests, fuzzing); `file_name` is used in messages and to resolve
/// relative paths (sensor files). Bounded for any text: with `allow_huge` off, at most 10^7
/// sensors and 10^6 robots are built and aliases repeat at most 10^5 nodes, so 64 KiB of input
/// cannot take more than about 300 MB or a second (docs/scenario-reference.md, "Limits").
LoadResult load_scenario_text(const std::string& text, const std::string& file_name,
                              const std::vector<std::string>& overrides,
                              std::optional<std::uint64_t> seed = std::nullopt,
                              const LoadOptions& options = {});

}  // namespace masnet::scenarios
