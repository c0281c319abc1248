#pragma once
// The computation load in summary.json's `protocol.geometry` (docs/outputs.md): the half-plane
// clips and point-in-cell tests of the run's updates, in all and per update, and the tests the
// sensors made deciding whether to answer a SENSE.
#include <cstddef>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "protocols/geometry.hpp"

namespace masnet::scenarios {

/// {half_plane_clips, point_in_cell_tests, clips_per_update, point_tests_per_update,
/// sensor_point_tests, sensor_point_tests_per_update}: `robots` summed over the run's
/// `updates` updates, `sensor_tests` the sensors' count. Per-update values are null without
/// updates.
nlohmann::json geometry_summary(const protocols::GeometryWork& robots, std::uint64_t sensor_tests,
                                std::size_t updates);

}  // namespace masnet::scenarios
