#include "scenarios/report/run_data.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "scenarios/report/figure_parts.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using figure_parts::kNaN;
using figure_parts::point;
using figure_parts::points;
using nlohmann::json;
using plot::Point;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::optional<double> parse_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  double v = 0;
  const char* first = s.data();
  if (*first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error("'" + path.string() + "' is not valid JSON: " + e.what());
  }
}

}  // namespace

Table Table::read(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  Table t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("'" + path.string() + "' is empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  t.names_ = split(line);
  const std::size_t n = t.names_.size();
  t.numbers_.resize(n);
  t.text_.resize(n);
  std::vector<bool> textual(n, false);
  for (std::size_t row = 2; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<std::string> cells = split(line);
    if (cells.size() != n)
      throw std::runtime_error(
          fmt::format("{}:{}: {} fields, the header has {}", path.string(), row, cells.size(), n));
    for (std::size_t c = 0; c < n; ++c) {
      const std::optional<double> v = parse_number(cells[c]);
      t.numbers_[c].push_back(v ? *v : kNaN);
      if (!v && !cells[c].empty()) textual[c] = true;
      t.text_[c].push_back(std::move(cells[c]));
    }
  }
  // Keep the text only where it says more than the numbers.
  for (std::size_t c = 0; c < n; ++c)
    if (!textual[c]) std::vector<std::string>().swap(t.text_[c]);
  return t;
}

std::size_t Table::index(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  return names_.size();
}

bool Table::has(std::string_view name) const {
  return index(name) < names_.size();
}

const std::vector<double>& Table::column(std::string_view name) const {
  const std::size_t i = index(name);
  if (i == names_.size()) throw std::out_of_range("no column '" + std::string(name) + "'");
  return numbers_[i];
}

const std::vector<std::string>& Table::text(std::string_view name) const {
  const std::size_t i = index(name);
  if (i == names_.size()) throw std::out_of_range("no column '" + std::string(name) + "'");
  return text_[i];
}

RunData load_run_data(const fs::path& dir) {
  RunData run;
  run.dir = dir;
  if (!fs::is_directory(dir)) throw std::runtime_error("'" + dir.string() + "' is not a directory");
  run.summary = read_json(dir / "summary.json");
  run.timeseries = Table::read(dir / "timeseries.csv");
  run.trajectories = Table::read(dir / "trajectories.csv");
  run.nodes = Table::read(dir / "nodes.csv");
  if (fs::exists(dir / "updates.csv")) run.updates = Table::read(dir / "updates.csv");
  if (fs::exists(dir / "formation.csv")) run.formation = Table::read(dir / "formation.csv");
  if (fs::exists(dir / "followers.csv")) run.followers = Table::read(dir / "followers.csv");
  run.snapshots =
      fs::exists(dir / "snapshots.json") ? read_json(dir / "snapshots.json") : json::array();
  if (!run.snapshots.is_array())
    throw std::runtime_error("'" + (dir / "snapshots.json").string() + "' is not a list");
  // Older runs and runs with output.replay: false have none; a present file must be whole.
  if (fs::exists(dir / "replay.json")) {
    run.replay = read_json(dir / "replay.json");
    if (!run.replay.is_object() || !run.replay.contains("header") ||
        !run.replay["header"].is_object() || !run.replay.contains("frames") ||
        !run.replay["frames"].is_array())
      throw std::runtime_error("'" + (dir / "replay.json").string() +
                               "' is not {\"header\": {...}, \"frames\": [...]}");
  }

  try {
    const json& scenario = run.summary.at("scenario");
    run.name = scenario.value("name", std::string("run"));
    const json& resolved = scenario.value("resolved", json::object());
    run.field_kind =
        resolved.contains("field") ? resolved["field"].value("kind", std::string()) : std::string();
    run.duration_s = run.summary.value("sim_time_s", resolved.value("duration", 0.0));
    const json domain = resolved.value("domain", json::object());
    if (domain.contains("polygon") && domain["polygon"].is_array() &&
        domain["polygon"].size() >= 3) {
      run.domain = points(domain["polygon"]);
    } else if (domain.contains("rectangle") && domain["rectangle"].size() == 4) {
      const json& r = domain["rectangle"];
      const double x0 = r[0], y0 = r[1], x1 = r[2], y1 = r[3];
      run.domain = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    } else {
      run.domain = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    }
  } catch (const json::exception& e) {
    throw std::runtime_error("'" + (dir / "summary.json").string() +
                             "': bad scenario section: " + e.what());
  }

  if (fs::exists(dir / "sensors.csv")) {
    const Table sensors = Table::read(dir / "sensors.csv");
    const auto &x = sensors.column("x"), &y = sensors.column("y");
    for (std::size_t i = 0; i < x.size(); ++i)
      run.sensors.push_back({x[i], y[i]});
  } else if (run.nodes.has("role") && run.nodes.has("index")) {
    const auto& role = run.nodes.text("role");
    const auto &index = run.nodes.column("index"), &x = run.nodes.column("x"),
               &y = run.nodes.column("y");
    std::vector<std::pair<double, Point>> rows;
    for (std::size_t i = 0; i < role.size(); ++i)
      if (role[i] == "sensor") rows.push_back({index[i], {x[i], y[i]}});
    std::stable_sort(rows.begin(), rows.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& r : rows)
      run.sensors.push_back(r.second);
  }
  return run;
}

}  // namespace masnet::scenarios
