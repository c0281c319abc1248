#pragma once
// Shared by the sweep's own files only: the parser of sweep files (sweep_parser.cpp, its axes in
// sweep_parser_axes.cpp, its `report` in sweep_parser_report.cpp) and the hash that names base
// scenarios and runs (sweep_expansion.cpp).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

#include "scenarios/loader/reader.hpp"
#include "scenarios/sweep/sweep.hpp"

namespace masnet::scenarios::sweep_parsing {
using nlohmann::json;

/// FNV-1a 64 with a splitmix64 finish (run ids and base keys).
std::uint64_t fnv1a64(std::string_view text);
/// 16 lower-case hex digits.
std::string hex16(std::uint64_t h);

/// A YAML value as JSON: plain scalars become integers, numbers or booleans when they read as
/// such, quoted scalars stay texts. JSON is YAML, so value.dump() is a valid --set VALUE.
json yaml_to_json(const YAML::Node& node);
/// A value as a run label shows it: texts without quotes.
std::string value_label(const json& v);
/// Decimals a number is written with: "0.25" -> 2, "1e-3" -> 3, "5" -> 0.
int written_decimals(const std::string& text);
/// A dotted scenario key: [A-Za-z0-9_.], no empty part.
bool valid_key(const std::string& key);
/// The value of `key` in a YAML map (undefined when absent or not a map), never inserting.
YAML::Node child(const YAML::Node& map, const std::string& key);

// Each run's seed comes from `seeds` and replaces the scenario's `seed` after every override.
inline constexpr const char* kSeedKey =
    "'seed' cannot be overridden: every run gets its seed from 'seeds' (a count or a list)";

class SweepParser {
 public:
  explicit SweepParser(const std::string& file_name) : reader_(file_name, {}), file_(file_name) {}

  SweepLoad parse(const std::string& text);

 private:
  std::string at(const YAML::Node& node, const std::string& path) const {
    return reader_.location(node, path);
  }
  void error(const YAML::Node& node, const std::string& path, const std::string& message) {
    reader_.error(at(node, path), message);
  }
  void check_top_keys(const YAML::Node& root);
  void read_seeds(const YAML::Node& node);
  void read_set(const YAML::Node& node);
  void read_variants(const YAML::Node& node);
  // One varied key: its values, or nothing (error reported).
  std::optional<std::vector<json>> read_values(const std::string& key, const YAML::Node& node);
  void read_vary_and_zip(const YAML::Node& vary, const YAML::Node& zip);
  // `report` (sweep_parser_report.cpp), after the axes are known.
  void read_report(const YAML::Node& node);
  // The number of runs, from the axes' sizes, before anything is expanded.
  void check_run_count(const YAML::Node& root);
  void probe();

  ScenarioReader reader_;
  std::string file_;
  SweepDef def_;
  // Where each override key is first given in the sweep file, for probe errors.
  std::map<std::string, std::string> key_location_;
};

}  // namespace masnet::scenarios::sweep_parsing
