#include "scenarios/run/geometry_outputs.hpp"

namespace masnet::scenarios {

nlohmann::json geometry_summary(const protocols::GeometryWork& robots, std::uint64_t sensor_tests,
                                std::size_t updates) {
  auto per_update = [updates](std::uint64_t total) -> nlohmann::json {
    if (updates == 0) return nullptr;
    return static_cast<double>(total) / static_cast<double>(updates);
  };
  return {{"half_plane_clips", robots.half_plane_clips},
          {"point_in_cell_tests", robots.point_in_cell_tests},
          {"clips_per_update", per_update(robots.half_plane_clips)},
          {"point_tests_per_update", per_update(robots.point_in_cell_tests)},
          {"sensor_point_tests", sensor_tests},
          {"sensor_point_tests_per_update", per_update(sensor_tests)}};
}

}  // namespace masnet::scenarios
