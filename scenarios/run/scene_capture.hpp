#pragma once
// The picture of a run at one instant — robots, their cells and the oracle's, targets, the
// density raster, who transmitted — as compact JSON (docs/live-and-replay.md, "Frames"). The
// live viewer streams these frames and replay.json stores them; both are drawn by the same
// page code. Capturing only reads the world (no event, no draw from a random stream).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agents/world.hpp"
#include "scenarios/loader/scenario.hpp"

namespace masnet::scenarios {

struct Sample;

class SceneCapture {
 public:
  /// Positions are sent as whole numbers on a grid of kCoordinateSteps steps across the
  /// domain's bounding box: 0.1 mm on a 1 m domain, ~5 characters a coordinate.
  static constexpr double kCoordinateSteps = 10000.0;
  /// The density raster has at most this many bins along the domain's long side.
  static constexpr std::size_t kMaxRasterBins = 64;

  SceneCapture(agents::World& world, const ScenarioDef& def);

  /// What does not change during the run: the domain, the raster's grid, counts, names.
  nlohmann::json header() const;
  /// The state now, but `sent`; `latest` (may be null) adds the metric curves' latest values.
  nlohmann::json frame(const Sample* latest);
  /// The frames each robot transmitted since the previous call for the same `stream` (the
  /// replay and a watcher keep their own count): a frame's `sent`.
  nlohmann::json sent_since_last(std::size_t stream);

  std::size_t raster_nx() const { return raster_nx_; }
  std::size_t raster_ny() const { return raster_ny_; }

 private:
  std::int64_t qx(double x) const;
  std::int64_t qy(double y) const;
  nlohmann::json polygon(const std::vector<Vec2>& vertices) const;
  /// Mean noiseless reading per raster bin, scaled to 0…255 by the frame's largest bin.
  std::string raster(double& max_value);

  agents::World& world_;
  const ScenarioDef& def_;
  double x0_ = 0, y0_ = 0, x1_ = 1, y1_ = 1;
  std::size_t raster_nx_ = 0, raster_ny_ = 0;
  std::vector<std::uint32_t> sensor_bin_;
  std::vector<std::uint32_t> bin_sensor_count_;
  std::vector<double> bin_sum_;
  std::vector<std::vector<std::uint64_t>> robot_sent_;  // per stream: frames sent at its last call
};

/// Base64 of `bytes` (RFC 4648, with padding).
std::string base64(const std::vector<std::uint8_t>& bytes);

}  // namespace masnet::scenarios
