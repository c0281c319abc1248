// The node layouts of a scenario: sensors (grid, random, file) and robots (grid, positions,
// random), with the limits on their numbers checked before anything is built.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string_view>

#include "scenarios/loader/input.hpp"
#include "scenarios/loader/scenario_parts.hpp"
#include "sim/random.hpp"

namespace masnet::scenarios {

using protocols::ConvexPolygon;

std::string shown_point(const Vec2& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

namespace {

std::string opt_in_hint(const NodeCaps& caps, std::int64_t huge_cap) {
  if (caps.huge) return "";
  return " (limits.allow_huge: true allows up to " + std::to_string(huge_cap) + ")";
}

// Reports the nodes outside the domain: the first kMaxListed one by one, then how many more.
class OutsideList {
 public:
  explicit OutsideList(ScenarioReader& reader) : reader_(reader) {}
  void add(const std::string& location, const std::string& message) {
    if (++count_ <= kMaxListed)
      reader_.error(location, message);
    else if (first_unlisted_.empty())
      first_unlisted_ = location;
  }
  void finish(const std::string& what) {
    if (count_ > kMaxListed)
      reader_.error(first_unlisted_, "... and " + std::to_string(count_ - kMaxListed) + " more " +
                                         what + " outside the domain");
  }

 private:
  ScenarioReader& reader_;
  std::size_t count_ = 0;
  std::string first_unlisted_;
};

Vec2 box_low(const ConvexPolygon& domain) {
  Vec2 lo = domain.vertices[0];
  for (const Vec2& v : domain.vertices)
    lo = lo.cwiseMin(v);
  return lo;
}
Vec2 box_high(const ConvexPolygon& domain) {
  Vec2 hi = domain.vertices[0];
  for (const Vec2& v : domain.vertices)
    hi = hi.cwiseMax(v);
  return hi;
}

// Random layouts draw points in the bounding box and keep those inside Ω: in a sliver of a
// domain that takes count / fill draws, bounded like the other periodic work.
bool random_layout_fits(Section& s, const ConvexPolygon& domain, std::int64_t count,
                        const NodeCaps& caps) {
  const Vec2 lo = box_low(domain), hi = box_high(domain);
  const double fill = protocols::area(domain) / ((hi.x() - lo.x()) * (hi.y() - lo.y()));
  const double draws = static_cast<double>(count) / fill;
  const double limit = caps.huge ? kMaxPeriodicWork : kMaxRandomDraws;
  if (draws <= limit) return true;
  std::ostringstream text;
  text << "layout random would draw about " << draws << " points (the domain fills " << fill * 100.0
       << "% of its bounding box), more than the limit of " << limit << "; use fewer nodes"
       << (caps.huge ? "" : ", or set limits.allow_huge: true");
  s.error_at("count", text.str());
  return false;
}

// A sensor file's columns: x, y and an optional area in that order, and, when the header
// names it, a `battery` column anywhere.
struct SensorColumns {
  std::optional<std::size_t> battery;  // its index
  std::size_t count = 0;               // columns per line when there is a battery column
  std::string names;                   // "x,y,battery", for messages
};

// The header line (the first, when it is not numbers): `fields` are its cells, `starts` their
// byte offsets. Only a `battery` column changes how lines are read.
void read_sensor_header(const std::vector<std::string>& fields,
                        const std::vector<std::size_t>& starts, const std::string& at,
                        ScenarioReader& reader, SensorColumns& columns) {
  const auto trimmed = [](std::string f) {
    while (!f.empty() && (f.back() == ' ' || f.back() == '\r'))
      f.pop_back();
    return f.substr(std::min(f.find_first_not_of(' '), f.size()));
  };
  for (std::size_t k = 0; k < fields.size(); ++k) {
    if (trimmed(fields[k]) != "battery") continue;
    if (columns.battery) {
      reader.error(at + std::to_string(starts[k] + 1), "the header names 'battery' twice");
      columns.battery.reset();
      return;
    }
    columns.battery = k;
  }
  if (!columns.battery) return;
  if (fields.size() != 3 && fields.size() != 4) {
    reader.error(at + "1",
                 "a header with a 'battery' column has 3 or 4 columns (x,y[,area] and "
                 "battery), got " +
                     std::to_string(fields.size()));
    columns.battery.reset();
    return;
  }
  columns.count = fields.size();
  const char* positional[] = {"x", "y", "area"};
  for (std::size_t k = 0, other = 0; k < fields.size(); ++k)
    columns.names +=
        std::string(k ? "," : "") + (k == *columns.battery ? "battery" : positional[other++]);
}

// `lines` receives the line number of each sensor, to locate later checks in the CSV file.
std::vector<agents::SensorDef> read_sensor_file(const std::string& path, Section& s,
                                                ScenarioReader& reader, std::vector<int>& lines,
                                                const NodeCaps& caps) {
  std::vector<agents::SensorDef> sensors;
  std::string text, problem;
  if (!read_regular_file(path, kMaxSensorFileBytes, text, problem)) {
    s.error_at("file", "cannot read sensor file '" + shown_text(path) + "' (" + problem + ")");
    return sensors;
  }
  SensorColumns columns;
  std::string_view rest(text);
  int number = 0;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string line(rest.substr(0, end));
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> cols;
    std::vector<std::string> texts;
    std::vector<std::size_t> starts;  // 0-based byte offset of each field
    std::stringstream fields(line);
    std::string field;
    std::size_t column = 0, bad_column = 0;  // 0-based offset of the first non-number
    std::string bad_field;
    bool numeric = true;
    while (std::getline(fields, field, ',')) {
      const std::size_t width = field.size() + 1;  // with its comma (or its line's end)
      if (!field.empty() && field.back() == '\r') field.pop_back();
      char* parsed_end = nullptr;
      const double v = std::strtod(field.c_str(), &parsed_end);
      while (parsed_end && *parsed_end == ' ')
        ++parsed_end;
      if (numeric && (parsed_end == field.c_str() || (parsed_end && *parsed_end != '\0'))) {
        numeric = false;
        bad_column = column;
        bad_field = field;
      }
      cols.push_back(v);
      texts.push_back(field);
      starts.push_back(column);
      column += width;
    }
    const std::string at = path + ":" + std::to_string(number) + ":";
    if (!numeric) {
      if (number == 1) {  // a header line
        read_sensor_header(texts, starts, at, reader, columns);
        continue;
      }
      const std::string lines_are =
          columns.battery ? "'" + columns.names + "'" : "'x,y' or 'x,y,area'";
      reader.error(
          at + std::to_string(bad_column + 1),
          "expected a number, got '" + shown_text(bad_field) + "' (lines are " + lines_are + ")");
      continue;
    }
    double battery_j = 0.0;
    if (columns.battery) {
      if (cols.size() != columns.count) {
        reader.error(at + "1", "expected " + std::to_string(columns.count) + " columns (" +
                                   columns.names + ", as the header says), got " +
                                   std::to_string(cols.size()));
        continue;
      }
      const std::size_t b = *columns.battery;
      battery_j = cols[b];
      if (!(battery_j >= 0.0 && battery_j <= kMaxMagnitude)) {
        reader.error(at + std::to_string(starts[b] + 1),
                     "the battery (column " + std::to_string(b + 1) +
                         ") must be in [0, 1e+12] J (got '" + shown_text(texts[b]) + "')");
        continue;
      }
      cols.erase(cols.begin() + static_cast<std::ptrdiff_t>(b));
    } else if (cols.size() != 2 && cols.size() != 3) {
      reader.error(at + "1",
                   "expected 2 or 3 columns (x,y[,area]), got " + std::to_string(cols.size()));
      continue;
    }
    if (!(std::fabs(cols[0]) <= kMaxMagnitude && std::fabs(cols[1]) <= kMaxMagnitude)) {
      reader.error(at + "1", "coordinates must be finite and within ±1e+12");
      continue;
    }
    if (cols.size() == 3 && !(cols[2] > 0.0 && cols[2] <= kMaxMagnitude * kMaxMagnitude)) {
      reader.error(at + "1", "the area (third column) must be > 0");
      continue;
    }
    if (static_cast<std::int64_t>(sensors.size()) == caps.sensors) {
      reader.error(at + "1", "more than " + std::to_string(caps.sensors) + " sensors" +
                                 opt_in_hint(caps, kMaxSensorsHuge));
      break;
    }
    agents::SensorDef d;
    d.position = Vec2{cols[0], cols[1]};
    d.area = cols.size() == 3 ? cols[2] : 0.0;
    d.battery_j = battery_j;
    sensors.push_back(d);
    lines.push_back(number);
  }
  return sensors;
}

}  // namespace

std::vector<agents::SensorDef> read_sensors(Section s, const ConvexPolygon& domain,
                                            std::uint64_t seed, const std::string& base_dir,
                                            ScenarioReader& reader, SensorLayout& layout,
                                            agents::WorldDef& world, const NodeCaps& caps) {
  std::vector<agents::SensorDef> sensors;
  layout.kind = s.choice<std::string>("layout", "grid",
                                      {{"grid", "grid"}, {"random", "random"}, {"file", "file"}});
  world.sensor_noise_sigma = s.number("noise", 0.0, Range::non_negative());
  world.sensor_battery_j = s.number("battery", 0.0, Range::non_negative());
  const Vec2 lo = box_low(domain), hi = box_high(domain);
  const double domain_area = protocols::area(domain);
  std::size_t count = 0;
  if (layout.kind == "grid") {
    auto nx = s.integer("nx", 10, 1, 100000), ny = s.integer("ny", 10, 1, 100000);
    // Checked before anything is built: a typo must not exhaust memory while validating.
    if (nx * ny > caps.sensors) {
      s.error_at("ny", "a " + std::to_string(nx) + " x " + std::to_string(ny) +
                           " grid has more than " + std::to_string(caps.sensors) + " sensors" +
                           opt_in_hint(caps, kMaxSensorsHuge));
      nx = ny = 1;
    }
    const std::string alignment = s.choice<std::string>("alignment", "cell_centred",
                                                        {{"cell_centred", "cell_centred"},
                                                         {"node_aligned", "node_aligned"},
                                                         {"interior", "interior"}});
    const double w = hi.x() - lo.x(), h = hi.y() - lo.y();
    // cell_centred: the centres of an nx × ny grid of cells (the paper's 40 × 40 sensors);
    // node_aligned: nx × ny nodes from wall to wall; interior: the inner nodes of an
    // (nx+1) × (ny+1)-interval grid (the 29 × 29 sensors of Diff-MAS2D's 30 × 30 grid).
    if (caps.build_sensors) sensors.reserve(static_cast<std::size_t>(nx * ny));
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        double x, y;
        if (alignment == "cell_centred") {
          x = lo.x() + (static_cast<double>(i) + 0.5) * w / static_cast<double>(nx);
          y = lo.y() + (static_cast<double>(j) + 0.5) * h / static_cast<double>(ny);
        } else if (alignment == "interior") {
          x = lo.x() + static_cast<double>(i + 1) * w / static_cast<double>(nx + 1);
          y = lo.y() + static_cast<double>(j + 1) * h / static_cast<double>(ny + 1);
        } else {
          x = nx == 1 ? lo.x() + 0.5 * w
                      : lo.x() + static_cast<double>(i) * w / static_cast<double>(nx - 1);
          y = ny == 1 ? lo.y() + 0.5 * h
                      : lo.y() + static_cast<double>(j) * h / static_cast<double>(ny - 1);
        }
        const Vec2 p{x, y};
        if (!protocols::contains(domain, p)) continue;
        ++count;
        if (caps.build_sensors) sensors.push_back({p, 0.0});
      }
    const auto intervals = [&](std::int64_t n) {
      return static_cast<double>(alignment == "cell_centred" ? n
                                 : alignment == "interior"   ? n + 1
                                                             : std::max<std::int64_t>(n - 1, 1));
    };
    layout.spacing = std::min(w / intervals(nx), h / intervals(ny));
  } else {
    s.reject("nx", "'nx' applies to layout grid");
    s.reject("ny", "'ny' applies to layout grid");
    s.reject("alignment", "'alignment' applies to layout grid");
  }
  if (layout.kind == "random") {
    auto wanted = s.integer("count", 100, 0, kMaxSensorsHuge);
    if (wanted > caps.sensors) {
      s.error_at("count", "more than " + std::to_string(caps.sensors) + " sensors (got " +
                              std::to_string(wanted) + ")" + opt_in_hint(caps, kMaxSensorsHuge));
      wanted = 0;
    }
    if (!random_layout_fits(s, domain, wanted, caps)) wanted = 0;
    count = static_cast<std::size_t>(wanted);
    if (caps.build_sensors) {
      sensors.reserve(count);
      auto rng = sim::RandomStream::keyed(seed, std::uint64_t{0}, sim::purpose("sensors.layout"));
      // Rejection sampling in the bounding box keeps the layout uniform in any convex domain.
      while (sensors.size() < count) {
        const Vec2 p{rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y())};
        if (protocols::contains(domain, p)) sensors.push_back({p, 0.0});
      }
    }
  } else {
    s.reject("count", "'count' applies to layout random");
  }
  if (layout.kind == "file") {
    std::string file = s.text("file", "");
    if (file.empty()) {
      s.error_at("file", "layout file needs 'file: path/to/sensors.csv'");
    } else {
      if (std::filesystem::path(file).is_relative())
        file = (std::filesystem::path(base_dir) / file).string();
      std::vector<int> lines;
      sensors = read_sensor_file(file, s, reader, lines, caps);
      OutsideList outside(reader);
      for (std::size_t k = 0; k < sensors.size(); ++k)
        if (!protocols::contains(domain, sensors[k].position))
          outside.add(file + ":" + std::to_string(lines[k]) + ":1",
                      "sensor " + std::to_string(k) + " at " + shown_point(sensors[k].position) +
                          " lies outside the domain");
      outside.finish("sensors");
      count = sensors.size();
    }
  } else {
    s.reject("file", "'file' applies to layout file");
  }
  s.finish();
  layout.count = count;
  if (layout.kind != "grid" && count > 0)
    layout.spacing = std::sqrt(domain_area / static_cast<double>(count));
  // Every sensor stands for an equal share of Ω unless the file says otherwise.
  for (auto& d : sensors)
    if (d.area <= 0.0) d.area = domain_area / static_cast<double>(sensors.size());
  return sensors;
}

std::vector<Vec2> read_robots(Section s, const ConvexPolygon& domain, std::uint64_t seed,
                              agents::WorldDef& world, const NodeCaps& caps) {
  std::vector<Vec2> robots;
  const std::string layout = s.choice<std::string>(
      "layout", "grid", {{"grid", "grid"}, {"positions", "positions"}, {"random", "random"}});
  const Vec2 lo = box_low(domain), hi = box_high(domain);
  if (layout == "grid") {
    // Cell-centred: 3 × 3 on the unit square gives 1/6, 1/2, 5/6 (the paper's §VI-A start).
    auto nx = s.integer("nx", 3, 1, 10000), ny = s.integer("ny", 3, 1, 10000);
    if (nx * ny > caps.robots) {
      s.error_at("ny", "a " + std::to_string(nx) + " x " + std::to_string(ny) +
                           " grid has more than " + std::to_string(caps.robots) + " robots" +
                           opt_in_hint(caps, kMaxRobotsHuge));
      nx = ny = 1;
    }
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i)
        robots.push_back(Vec2{
            lo.x() + (static_cast<double>(i) + 0.5) * (hi.x() - lo.x()) / static_cast<double>(nx),
            lo.y() + (static_cast<double>(j) + 0.5) * (hi.y() - lo.y()) / static_cast<double>(ny)});
    // The grid spans Ω's bounding box; in a non-rectangular Ω some of it may fall outside.
    OutsideList outside(s.reader());
    for (std::size_t i = 0; i < robots.size(); ++i)
      if (!protocols::contains(domain, robots[i]))
        outside.add(s.where("layout"),
                    s.path() + ".layout: robot " + std::to_string(i) + " of the " +
                        std::to_string(nx) + " x " + std::to_string(ny) + " grid, at " +
                        shown_point(robots[i]) +
                        ", lies outside the domain (use layout positions or random)");
    outside.finish("robots");
  } else {
    s.reject("nx", "'nx' applies to layout grid");
    s.reject("ny", "'ny' applies to layout grid");
  }
  if (layout == "positions") {
    if (!s.has("positions"))
      s.error_at("positions", "layout positions needs 'positions: [[x, y], ...]'");
    robots = s.points("positions", 1);
    if (static_cast<std::int64_t>(robots.size()) > caps.robots) {
      s.error_at("positions", "more than " + std::to_string(caps.robots) + " robots" +
                                  opt_in_hint(caps, kMaxRobotsHuge));
      robots.clear();
    }
    OutsideList outside(s.reader());
    for (std::size_t i = 0; i < robots.size(); ++i)
      if (!protocols::contains(domain, robots[i]))
        outside.add(s.where("positions"), s.path() + ".positions: robot " + std::to_string(i) +
                                              " at " + shown_point(robots[i]) +
                                              " lies outside the domain");
    outside.finish("robots");
  } else {
    s.reject("positions", "'positions' applies to layout positions");
  }
  if (layout == "random") {
    auto count = s.integer("count", 9, 1, kMaxRobotsHuge);
    if (count > caps.robots) {
      s.error_at("count", "more than " + std::to_string(caps.robots) + " robots (got " +
                              std::to_string(count) + ")" + opt_in_hint(caps, kMaxRobotsHuge));
      count = 0;
    }
    if (!random_layout_fits(s, domain, count, caps)) count = 0;
    auto rng = sim::RandomStream::keyed(seed, std::uint64_t{0}, sim::purpose("robots.layout"));
    while (static_cast<std::int64_t>(robots.size()) < count) {
      const Vec2 p{rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y())};
      if (protocols::contains(domain, p)) robots.push_back(p);
    }
  } else {
    s.reject("count", "'count' applies to layout random");
  }
  agents::MotionParams& motion = world.motion;
  motion.k = s.number("k", 3.0, Range::non_negative());
  motion.k_v = s.number("k_v", 1.0, Range::non_negative());
  motion.max_speed = s.number("max_speed", 0.0, Range::non_negative());
  motion.substep_s = s.number("substep", 1e-3, Range::time());
  motion.jump_to_target =
      s.choice<bool>("dynamics", false, {{"second_order", false}, {"discrete_lloyd", true}});
  world.actuation_delay_s = s.number("actuation_delay", 0.0, Range::delay());
  world.robot_battery_j = s.number("battery", 0.0, Range::non_negative());
  world.locomotion = read_locomotion(s.section("energy"));
  // Read only when present: a scenario without groups resolves exactly as before.
  if (s.has("groups"))
    world.formation = read_groups(s.section("groups"), robots.size(), caps);
  else
    s.mark_known("groups");
  s.finish();
  return robots;
}

}  // namespace masnet::scenarios
