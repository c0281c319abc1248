#include "scenarios/loader/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "scenarios/loader/input.hpp"
#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {
namespace {

using agents::FieldKind;
using protocols::ConvexPolygon;

// ---- --set overrides -------------------------------------------------------------------------

struct Override {
  std::string path;  // "radio.loss"
  std::string text;  // "radio.loss=0.2"
  YAML::Node value;
};

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  std::string part;
  while (std::getline(in, part, '.'))
    parts.push_back(part);
  return parts;
}

// Parses "a.b=v" and writes v into the tree, creating mappings on the way.
bool apply_override(YAML::Node& root, const std::string& text, std::vector<Override>& applied,
                    std::vector<Diagnostic>& diagnostics) {
  const auto eq = text.find('=');
  const std::string where = "--set " + shown_text(text);
  if (eq == std::string::npos || eq == 0) {
    diagnostics.push_back({where, "expected KEY.PATH=VALUE"});
    return false;
  }
  const std::string path = text.substr(0, eq);
  const std::vector<std::string> parts = split_path(path);
  for (const auto& p : parts)
    if (p.empty()) {
      diagnostics.push_back({where, "empty key in '" + shown_text(path) + "'"});
      return false;
    }
  // The same checks as a file's text: valid UTF-8 (summary.json is JSON), no tags, bounded aliases.
  if (auto problems = check_yaml_text(text.substr(eq + 1), "", where); !problems.empty()) {
    diagnostics.insert(diagnostics.end(), problems.begin(), problems.end());
    return false;
  }
  YAML::Node value;
  try {
    value = YAML::Load(text.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    diagnostics.push_back({where, "value is not valid YAML: " + shown_text(e.msg)});
    return false;
  }
  if (!root.IsMap()) root = YAML::Node(YAML::NodeType::Map);
  // Walk with reset(), never operator=: on a yaml-cpp Node, `a = b` rebinds the data that `a`
  // refers to, so `node = next` would overwrite the root with the subsection.
  YAML::Node node;
  node.reset(root);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node next;
    next.reset(node[parts[i]]);
    if (!next.IsDefined() || next.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next.reset(node[parts[i]]);
    } else if (!next.IsMap()) {
      std::string prefix;
      for (std::size_t k = 0; k <= i; ++k)
        prefix += (k ? "." : "") + parts[k];
      diagnostics.push_back({where, "'" + shown_text(prefix) + "' is not a section, cannot set '" +
                                        shown_text(path) + "'"});
      return false;
    }
    node.reset(next);
  }
  node[parts.back()] = value;
  applied.push_back({path, text, value});
  return true;
}

// ---- Sections --------------------------------------------------------------------------------

ConvexPolygon read_domain(Section s) {
  ConvexPolygon domain = protocols::rectangle(0, 0, 1, 1);
  const bool has_rect = s.has("rectangle"), has_poly = s.has("polygon");
  if (has_rect && has_poly) s.error_at("polygon", "give either 'rectangle' or 'polygon', not both");
  if (has_rect) {
    const std::vector<double> r = s.numbers("rectangle");
    if (r.size() != 4 || !(r[0] < r[2]) || !(r[1] < r[3]))
      s.error_at("rectangle", "expected [xmin, ymin, xmax, ymax] with xmin < xmax and ymin < ymax");
    else
      domain = protocols::rectangle(r[0], r[1], r[2], r[3]);
  } else {
    s.numbers("rectangle");
  }
  if (has_poly) {
    const std::vector<Vec2> points = s.points("polygon", 3);
    if (points.size() >= 3) {
      if (!protocols::is_simple(points))
        s.error_at("polygon", "the polygon intersects itself");
      else if (auto canonical = protocols::normalize_convex_polygon(points)) {
        if (!has_rect) domain = *canonical;  // both given: reported above, keep the default
      } else
        s.error_at("polygon", "the polygon is not convex (the domain must be a convex polygon)");
    }
  } else {
    s.points("polygon");
  }
  s.finish();
  return domain;
}

agents::PathDef read_path(Section& s) {
  agents::PathDef path;
  path.waypoints = s.points("waypoints");
  if (!path.waypoints.empty()) {
    path.speed = s.number("speed", 0.1, Range::non_negative());
    path.loop = s.boolean("loop", false);
    s.reject("start", "give either 'start' (with 'velocity') or 'waypoints', not both");
    s.reject("center", "give either 'center' (with 'velocity') or 'waypoints', not both");
    s.reject("velocity", "'velocity' goes with 'start'; waypoints move at 'speed'");
  } else {
    if (!s.has("start") && !s.has("center"))
      s.error_at("start", "missing 'start: [x, y]' (or 'waypoints')");
    if (s.has("center"))
      s.reject("start", "give either 'start' or 'center' (the same thing), not both");
    s.mark_known("center");  // `center` is the same key as `start`, for bumps
    path.start =
        s.has("center") ? s.point("center", Vec2{0.5, 0.5}) : s.point("start", Vec2{0.5, 0.5});
    path.velocity = s.point("velocity", Vec2{0, 0});
    s.reject("speed", "'speed' goes with 'waypoints'");
    s.reject("loop", "'loop' goes with 'waypoints'");
  }
  return path;
}

agents::FieldDef read_field(Section s, const ConvexPolygon& domain) {
  agents::FieldDef f;
  f.kind = s.choice<FieldKind>("kind", FieldKind::uniform,
                               {{"uniform", FieldKind::uniform},
                                {"acoustic", FieldKind::acoustic},
                                {"gaussian", FieldKind::gaussian},
                                {"diffusion", FieldKind::diffusion}});
  const std::string only = "' applies to field kind ";
  if (f.kind == FieldKind::uniform) {
    f.uniform_value = s.number("value", 1.0, Range::positive());
  } else {
    s.reject("value", "'value" + only + "uniform");
  }
  if (f.kind == FieldKind::acoustic) {
    f.amplitude = s.number("amplitude", 1.0, Range::positive());
    f.alpha = s.number("alpha", 2.0, Range::positive());
    if (s.has("min_distance") && s.text("min_distance", "auto") != "auto")
      f.min_distance = s.number("min_distance", 0.0, Range::positive());
    else
      f.min_distance = 0.0;  // auto: half the sensor spacing, set by the builder
    for (Section t : s.sections("targets")) {
      f.targets.push_back(read_path(t));
      t.finish();
    }
    if (f.targets.empty()) s.error_at("targets", "an acoustic field needs at least one target");
  } else {
    for (const char* key : {"amplitude", "alpha", "min_distance", "targets"})
      s.reject(key, std::string("'") + key + only + "acoustic");
  }
  if (f.kind == FieldKind::gaussian) {
    for (Section b : s.sections("bumps")) {
      agents::GaussianBump bump;
      bump.path = read_path(b);
      bump.sigma = b.number("sigma", 0.1, Range::positive());
      bump.amplitude = b.number("amplitude", 1.0, Range::positive());
      b.finish();
      f.bumps.push_back(bump);
    }
    if (f.bumps.empty()) s.error_at("bumps", "a gaussian field needs at least one bump");
  } else {
    s.reject("bumps", "'bumps" + only + "gaussian");
  }
  if (f.kind == FieldKind::diffusion) {
    Section d = s.section("diffusion");
    agents::DiffusionParams& p = f.diffusion;
    p.mode = d.choice<agents::DiffusionMode>("mode", agents::DiffusionMode::fidelity,
                                             {{"fidelity", agents::DiffusionMode::fidelity},
                                              {"physical", agents::DiffusionMode::physical}});
    p.boundary = d.choice<agents::Boundary>(
        "boundary", agents::Boundary::dirichlet,
        {{"dirichlet", agents::Boundary::dirichlet}, {"no_flux", agents::Boundary::no_flux}});
    p.kappa = d.number("kappa", p.kappa, Range::positive());
    p.cells = static_cast<int>(d.integer("cells", p.cells, 2, 4096));
    p.cells_y = static_cast<int>(d.integer("cells_y", 0, 0, 4096));
    p.dt_s = d.number("dt", p.dt_s, Range::time());
    d.mark_known("clip");  // absent: the mode's default (docs/field-models.md)
    if (d.has("clip")) p.clip_sprays_at_zero = d.boolean("clip", false);
    // The PDE lives on a rectangle: Ω must be one, and gives the grid its extent.
    Vec2 lo = domain.vertices[0], hi = domain.vertices[0];
    for (const Vec2& v : domain.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    const double box = (hi.x() - lo.x()) * (hi.y() - lo.y());
    if (domain.vertices.size() != 4 || std::fabs(protocols::area(domain) - box) > 1e-12 * box)
      s.error_at("kind", "a diffusion field needs a rectangular domain");
    p.x0 = lo.x();
    p.y0 = lo.y();
    p.x1 = hi.x();
    p.y1 = hi.y();
    if (std::string problem = agents::diffusion_params_error(p); !problem.empty() && d.has("dt"))
      d.error_at("dt", problem);
    else if (!problem.empty())
      d.error_at("cells", problem);
    d.finish();
    for (Section src : s.sections("sources")) {
      agents::SourceDef source;
      source.path = read_path(src);
      source.amplitude = src.number("amplitude", 20.0, Range::non_negative());
      source.decay = src.number("decay", 1.0, Range::non_negative());
      src.finish();
      f.sources.push_back(source);
    }
  } else {
    s.reject("diffusion", "'diffusion" + only + "diffusion");
    s.reject("sources", "'sources" + only + "diffusion");
  }
  s.finish();
  return f;
}

// The robots' dispensers and the uncontrolled twin run (diffusion fields only).
void read_control(Section s, bool diffusion, agents::DispenserDef& d, ScenarioDef& def) {
  if (!diffusion) {
    if (s.has("dispensers") || s.has("baseline") || s.has("gain"))
      s.error_at("dispensers", "the control section applies to field kind diffusion");
  }
  d.enabled = s.boolean("dispensers", false);
  d.gain = s.number("gain", d.gain, Range::non_negative());
  d.spray_radius = s.number("spray_radius", d.spray_radius, Range::positive());
  d.max_rate = s.number("max_rate", d.max_rate, Range::non_negative());
  d.payload = s.number("payload", d.payload, Range::non_negative());
  d.readings = s.choice<agents::SprayReadings>(
      "readings", d.readings,
      {{"live", agents::SprayReadings::live}, {"last_update", agents::SprayReadings::last_update}});
  def.baseline = s.boolean("baseline", false);
  def.clean_threshold = s.number("clean_threshold", 0.0, Range::non_negative());
  s.finish();
}

protocols::DensityScaling read_scaling(Section s) {
  using protocols::ScalingKind;
  protocols::DensityScaling sk;
  sk.kind = s.choice<ScalingKind>("kind", ScalingKind::identity,
                                  {{"identity", ScalingKind::identity},
                                   {"power", ScalingKind::power},
                                   {"log1p", ScalingKind::log1p},
                                   {"saturate", ScalingKind::saturate}});
  if (sk.kind == ScalingKind::power)
    sk.gamma = s.number("gamma", 1.0, Range::positive());
  else
    s.reject("gamma", "'gamma' applies to kind power");
  if (sk.kind == ScalingKind::saturate)
    sk.saturation = s.number("c", 1.0, Range::positive());
  else
    s.reject("c", "'c' applies to kind saturate");
  s.finish();
  return sk;
}

agents::BeaconDef read_beacons(Section s) {
  agents::BeaconDef b;
  b.senders = s.choice<agents::BeaconSenders>("senders", agents::BeaconSenders::none,
                                              {{"none", agents::BeaconSenders::none},
                                               {"robots", agents::BeaconSenders::robots},
                                               {"sensors", agents::BeaconSenders::sensors},
                                               {"all", agents::BeaconSenders::all}});
  b.period_s = s.number("period", b.period_s, Range::time());
  b.range = s.number("range", b.range, Range::positive());
  s.finish();
  return b;
}

OutputDef read_output(Section s, double duration_s, bool acoustic) {
  OutputDef o;
  o.sample_period_s = s.number("sample_period", o.sample_period_s, Range::time());
  o.trajectory_period_s = s.number("trajectory_period", o.trajectory_period_s, Range::time());
  o.snapshots = s.numbers("snapshots", Range{0.0, duration_s > 0 ? duration_s : kMaxTime_s});
  o.updates = s.boolean("updates", o.updates);
  o.figures = s.boolean("figures", o.figures);
  o.report = s.boolean("report", o.report);
  o.replay = s.boolean("replay", o.replay);
  // About 250 frames whatever the duration, never denser than the trajectories.
  o.replay_period_s =
      s.number("replay_period", std::max(o.trajectory_period_s, duration_s / 250.0), Range::time());
  if (!acoustic)
    s.reject("tracking_radius", "'tracking_radius' applies to field kind acoustic");
  else if (s.has("tracking_radius"))
    o.tracking_radius = s.number("tracking_radius", 0.0, Range::positive());
  else  // derived from the domain and the robots; left out of the resolved scenario so that
    s.mark_known("tracking_radius");  // run keys stay as they were before the key existed
  s.finish();
  return o;
}

}  // namespace

LoadResult load_scenario_text(const std::string& text, const std::string& file_name,
                              const std::vector<std::string>& overrides,
                              std::optional<std::uint64_t> seed, const LoadOptions& options) {
  LoadResult result;
  // The file name reaches summary.json ("source"): JSON text must be UTF-8.
  if (first_invalid_utf8(file_name) != std::string::npos) {
    result.diagnostics.push_back(
        {shown_text(file_name) + ":1:1", "the file name is not valid UTF-8"});
    return result;
  }
  result.diagnostics = check_yaml_text(text, file_name);
  if (!result.diagnostics.empty()) return result;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    result.diagnostics.push_back({file_name + ":" + std::to_string(e.mark.line + 1) + ":" +
                                      std::to_string(e.mark.column + 1),
                                  "YAML syntax error: " + shown_text(e.msg)});
    return result;
  }
  if (overrides.empty() && (!root.IsDefined() || root.IsNull())) {
    result.diagnostics.push_back(
        {file_name + ":1:1",
         "the scenario is empty (expected a mapping with at least 'duration')"});
    return result;
  }
  if (root.IsDefined() && !root.IsNull() && !root.IsMap()) {
    const YAML::Mark m = root.Mark();
    result.diagnostics.push_back(
        {file_name + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1),
         "the scenario must be a mapping of sections (name, duration, sensors, ...)"});
    return result;
  }
  std::vector<Override> applied;
  for (const std::string& o : overrides)
    apply_override(root, o, applied, result.diagnostics);
  if (!result.diagnostics.empty()) return result;

  std::vector<std::pair<std::string, std::string>> located;
  for (const Override& o : applied)
    located.emplace_back(o.path, o.text);
  ScenarioReader reader(file_name, located);
  Section top(reader, root, "", "");
  ScenarioDef def;
  def.source_path = file_name;
  // limits first: they decide how many nodes the layouts may build.
  const bool has_limits = top.has("limits");
  Section limits = top.section("limits");
  NodeCaps caps;
  caps.huge = limits.boolean("allow_huge", false) && options.allow_huge;
  limits.finish();
  if (!has_limits) reader.resolved().erase("limits");  // summary.json as before the key existed
  if (caps.huge) {
    caps.sensors = kMaxSensorsHuge;
    caps.robots = kMaxRobotsHuge;
  }
  caps.build_sensors = options.build_sensors;
  // The name becomes the run directory runs/<name>-seed<seed>: a file-name-safe token.
  const std::string stem = std::filesystem::path(file_name).stem().string();
  def.name = top.text("name", sanitized_name(stem));
  if (top.has("name") && !valid_name(def.name))
    top.error_at("name", "'" + shown_text(def.name) +
                             "' is not a valid name (it names the run directory: " + name_rule() +
                             ")");
  def.seed = static_cast<std::uint64_t>(
      top.integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
  if (seed) {
    def.seed = *seed;
    top.resolve("seed", static_cast<std::int64_t>(*seed));
  }
  // Absent, it stays out of summary.json (runs as before the key existed).
  const bool has_tie_order = top.has("tie_order");
  def.ties_by_origin =
      top.choice<bool>("tie_order", false, {{"scheduling", false}, {"origin", true}});
  if (!has_tie_order) reader.resolved().erase("tie_order");
  const std::size_t errors_before_duration = reader.diagnostics().size();
  if (!top.has("duration"))
    top.error_at("duration", "missing required key 'duration' (seconds of simulated time)");
  def.duration_s = top.number("duration", 1.0, Range::time());
  // Without a valid duration, snapshot times are not checked against the 1 s fallback.
  const bool duration_ok = reader.diagnostics().size() == errors_before_duration;
  def.world.seed = def.seed;
  def.world.domain = read_domain(top.section("domain"));
  const std::string base_dir = std::filesystem::path(file_name).parent_path().string();
  SensorLayout layout;
  NodeCounts counts;
  std::size_t errors_before = reader.diagnostics().size();
  def.world.sensors = read_sensors(top.section("sensors"), def.world.domain, def.seed, base_dir,
                                   reader, layout, def.world, caps);
  if (reader.diagnostics().size() == errors_before) counts.sensors = layout.count;
  def.sensor_count = layout.count;
  def.sensor_layout = layout.kind;
  LimitSections at{top.peek("field"),    top.peek("density_scaling"), top.peek("robots"),
                   top.peek("protocol"), top.peek("beacons"),         top.peek("output")};
  def.world.field = read_field(top.section("field"), def.world.domain);
  if (def.world.field.kind == FieldKind::acoustic && def.world.field.min_distance <= 0.0) {
    // d_min = h/2 by default: half the sensor spacing removes the singularity
    // (docs/decisions/0002-acoustic-field.md).
    def.world.field.min_distance = layout.spacing > 0 ? 0.5 * layout.spacing : 0.01;
    reader.resolved()[nlohmann::json::json_pointer("/field/min_distance")] =
        def.world.field.min_distance;
  }
  def.world.scaling = read_scaling(top.section("density_scaling"));
  errors_before = reader.diagnostics().size();
  def.world.robots =
      read_robots(top.section("robots"), def.world.domain, def.seed, def.world, caps);
  if (reader.diagnostics().size() == errors_before) counts.robots = def.world.robots.size();
  def.world.radio = read_radio(top.section("radio"));
  def.world.protocol = read_protocol(top.section("protocol"), def.world.radio.level);
  def.world.beacons = read_beacons(top.section("beacons"));
  read_control(top.section("control"), def.world.field.kind == FieldKind::diffusion,
               def.world.dispenser, def);
  def.output = read_output(top.section("output"), duration_ok ? def.duration_s : 0.0,
                           def.world.field.kind == FieldKind::acoustic);
  def.world.faults = read_faults(top, duration_ok ? def.duration_s : 0.0, counts);
  top.reject("groups", "robot groups are set under robots.groups (docs/formations.md)");
  top.finish();
  // What the numbers imply (work, densities) only means something once they are all valid.
  if (reader.ok()) check_limits(def, layout.count, caps, at);
  if (!reader.ok()) {
    result.known_keys = reader.known_paths();
    result.diagnostics = reader.diagnostics();
    // Sections are read in dependency order (domain before sensors and robots); report in the
    // order of the file, then --set and sensor-file problems in the order they were found.
    auto position = [&](const Diagnostic& d) {
      int line = 0, column = 0;
      const std::string prefix = file_name + ":";
      if (d.location.rfind(prefix, 0) == 0 &&
          std::sscanf(d.location.c_str() + prefix.size(), "%d:%d", &line, &column) == 2)
        return std::pair{line, column};
      return std::pair{std::numeric_limits<int>::max(), 0};
    };
    std::stable_sort(
        result.diagnostics.begin(), result.diagnostics.end(),
        [&](const Diagnostic& a, const Diagnostic& b) { return position(a) < position(b); });
    return result;
  }
  def.resolved = reader.resolved();
  result.scenario = std::move(def);
  result.warnings = reader.warnings();
  result.known_keys = reader.known_paths();
  return result;
}

LoadResult load_scenario(const std::string& path, const std::vector<std::string>& overrides,
                         std::optional<std::uint64_t> seed, const LoadOptions& options) {
  std::string text, problem;
  if (!read_regular_file(path, kMaxScenarioFileBytes, text, problem)) {
    LoadResult result;
    result.diagnostics.push_back(
        {path + ":1:1", "cannot read the scenario file (" + problem + ")"});
    return result;
  }
  return load_scenario_text(text, path, overrides, seed, options);
}

}  // namespace masnet::scenarios
