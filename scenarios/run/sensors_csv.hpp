#pragma once
// sensors.csv (docs/outputs.md): where the sensors stood, so that figures can be redrawn from the
// run directory alone.
#include <filesystem>
#include <vector>

#include "agents/world.hpp"

namespace masnet::scenarios {

/// Writes sensors.csv: index, x, y (world units) and area (world units², the part of Ω the
/// sensor stands for), one row per sensor in the order of snapshots.json's readings.
void write_sensors_csv(const std::filesystem::path& path, const agents::SensorList& sensors);

}  // namespace masnet::scenarios
