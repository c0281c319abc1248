#pragma once
// A run directory read back from its files alone — summary.json, snapshots.json, replay.json
// and the CSV files (docs/outputs.md) — for the figures and the report.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/report/plot/plot.hpp"

namespace masnet::scenarios {

/// One of our own CSV files read back (comma-separated, a header line, no quoting). Every
/// column is available as numbers (NaN where a cell is not a number) and as text.
class Table {
 public:
  /// Reads `path`; throws std::runtime_error when it cannot be opened.
  static Table read(const std::filesystem::path& path);

  std::size_t rows() const { return numbers_.empty() ? 0 : numbers_.front().size(); }
  bool has(std::string_view name) const;
  /// The column `name` as numbers; throws std::out_of_range when absent.
  const std::vector<double>& column(std::string_view name) const;
  /// The column `name` as written; throws std::out_of_range when absent.
  const std::vector<std::string>& text(std::string_view name) const;
  const std::vector<std::string>& names() const { return names_; }

 private:
  std::size_t index(std::string_view name) const;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> numbers_;
  std::vector<std::vector<std::string>> text_;
};

/// Everything the figures and the report need from a run directory.
struct RunData {
  std::filesystem::path dir;
  nlohmann::json summary;                 ///< summary.json
  nlohmann::json snapshots;               ///< snapshots.json (an array; empty when absent)
  nlohmann::json replay;                  ///< replay.json ({header, frames}); null when absent
  Table timeseries, trajectories, nodes;  ///< required files
  Table updates;                          ///< updates.csv; no rows when not written
  Table formation, followers;             ///< runs with robot groups; no rows otherwise
  std::vector<plot::Point> sensors;       ///< sensor positions, in reading order
  std::vector<plot::Point> domain;        ///< Ω's vertices (world units)
  std::string name;                       ///< scenario name
  std::string field_kind;                 ///< acoustic, diffusion, gaussian, uniform
  double duration_s = 0.0;
};

/// Reads the run directory `dir`. Sensor positions come from sensors.csv, or from the sensor
/// rows of nodes.csv in runs written before it existed. Throws std::runtime_error naming the
/// file that is missing or malformed.
RunData load_run_data(const std::filesystem::path& dir);

}  // namespace masnet::scenarios
