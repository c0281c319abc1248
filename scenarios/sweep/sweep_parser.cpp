#include "scenarios/sweep/sweep_parser.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "scenarios/loader/input.hpp"
#include "scenarios/loader/scenario.hpp"

namespace masnet::scenarios::sweep_parsing {
namespace fs = std::filesystem;

json yaml_to_json(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: {
      const std::string& s = node.Scalar();
      if (node.Tag() != "!") {
        long long i = 0;
        if (YAML::convert<long long>::decode(node, i)) return i;
        double d = 0;
        if (YAML::convert<double>::decode(node, d) && std::isfinite(d)) return d;
        if (s == "true" || s == "True" || s == "TRUE") return true;
        if (s == "false" || s == "False" || s == "FALSE") return false;
        if (s == "null" || s == "~") return nullptr;
      }
      return s;
    }
    case YAML::NodeType::Sequence: {
      json a = json::array();
      for (const auto& item : node)
        a.push_back(yaml_to_json(item));
      return a;
    }
    case YAML::NodeType::Map: {
      json o = json::object();
      for (auto it = node.begin(); it != node.end(); ++it)
        o[it->first.IsScalar() ? it->first.Scalar() : std::string("?")] = yaml_to_json(it->second);
      return o;
    }
    default:
      return nullptr;
  }
}

std::string value_label(const json& v) {
  return v.is_string() ? v.get<std::string>() : v.dump();
}

int written_decimals(const std::string& text) {
  std::string mantissa = text;
  int exponent = 0;
  if (const auto e = text.find_first_of("eE"); e != std::string::npos) {
    mantissa = text.substr(0, e);
    exponent = std::atoi(text.c_str() + e + 1);
  }
  int decimals = 0;
  if (const auto dot = mantissa.find('.'); dot != std::string::npos)
    decimals = static_cast<int>(mantissa.size() - dot - 1);
  return std::clamp(decimals - exponent, 0, 15);
}

bool valid_key(const std::string& key) {
  if (key.empty() || key.front() == '.' || key.back() == '.' || key.find("..") != std::string::npos)
    return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
  });
}

YAML::Node child(const YAML::Node& map, const std::string& key) {
  if (!map.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  for (auto it = map.begin(); it != map.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) return it->second;
  return YAML::Node(YAML::NodeType::Undefined);
}

// ---- Reading a sweep file ----------------------------------------------------------------------

void SweepParser::check_top_keys(const YAML::Node& root) {
  static const std::vector<std::string> known = {
      "name", "description", "base", "seeds", "set", "variants", "vary", "zip", "output", "report"};
  std::set<std::string> seen;
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
    if (!seen.insert(key).second) {
      error(it->first, key, "duplicate key '" + key + "'");
      continue;
    }
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string message = "unknown key '" + key +
                          "' in a sweep file (allowed: base, seeds, set, "
                          "variants, vary, zip, output, report, name, description)";
    if (auto guess = closest(key, known)) message += " (did you mean '" + *guess + "'?)";
    error(it->first, key, message);
  }
}

void SweepParser::read_seeds(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) {
    def_.seeds = {1};
    return;
  }
  if (node.IsScalar()) {
    long long n = 0;
    if (!YAML::convert<long long>::decode(node, n) || n < 1 || n > 1000000) {
      error(node, "seeds",
            "seeds: expected a count between 1 and 1000000 (seeds 1..N) or a list of seeds, got '" +
                node.Scalar() + "'");
      return;
    }
    for (long long s = 1; s <= n; ++s)
      def_.seeds.push_back(static_cast<std::uint64_t>(s));
    return;
  }
  if (!node.IsSequence() || node.size() == 0) {
    error(node, "seeds", "seeds: expected a count (seeds 1..N) or a non-empty list of seeds");
    return;
  }
  std::set<std::uint64_t> seen;
  for (std::size_t i = 0; i < node.size(); ++i) {
    long long s = -1;
    if (!node[i].IsScalar() || !YAML::convert<long long>::decode(node[i], s) || s < 0) {
      error(node[i], "seeds", "seeds[" + std::to_string(i) + "]: expected a whole number >= 0");
      continue;
    }
    if (!seen.insert(static_cast<std::uint64_t>(s)).second) {
      error(node[i], "seeds",
            "seeds[" + std::to_string(i) + "]: seed " + std::to_string(s) + " is listed twice");
      continue;
    }
    def_.seeds.push_back(static_cast<std::uint64_t>(s));
  }
}

void SweepParser::read_set(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsMap()) {
    error(node, "set", "set: expected a mapping of scenario keys to values, e.g. {duration: 2.0}");
    return;
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
    if (!valid_key(key)) {
      error(it->first, "set", "set: '" + key + "' is not a dotted scenario key like radio.loss");
      continue;
    }
    if (key == "seed") {
      error(it->first, "set", kSeedKey);
      continue;
    }
    key_location_.emplace(key, at(it->first, "set"));
    def_.set.push_back({key, yaml_to_json(it->second)});
  }
}

void SweepParser::read_variants(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsSequence() || node.size() == 0) {
    error(node, "variants",
          "variants: expected a list of mappings, each a 'name' and the keys it sets, e.g. "
          "- {name: oracle, protocol.kind: oracle}");
    return;
  }
  SweepAxis axis;
  axis.name = "variant";
  std::map<std::string, std::size_t> names;
  std::map<std::string, std::size_t> contents;  // canonical overrides -> variant
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node v = node[i];
    const std::string path = "variants[" + std::to_string(i) + "]";
    if (!v.IsMap()) {
      error(v, path, path + ": expected a mapping like {name: oracle, protocol.kind: oracle}");
      continue;
    }
    AxisPoint point;
    point.label = "v" + std::to_string(i + 1);
    json canonical = json::object();
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
      if (key == "name") {
        if (!it->second.IsScalar() || it->second.Scalar().empty()) {
          error(it->second, path, path + ".name: expected a text");
          continue;
        }
        point.label = it->second.Scalar();
        continue;
      }
      if (!valid_key(key)) {
        error(it->first, path,
              path + ": '" + key + "' is not a dotted scenario key like protocol.kind");
        continue;
      }
      if (key == "seed") {
        error(it->first, path, kSeedKey);
        continue;
      }
      key_location_.emplace(key, at(it->first, path));
      if (std::find(axis.keys.begin(), axis.keys.end(), key) == axis.keys.end())
        axis.keys.push_back(key);
      json value = yaml_to_json(it->second);
      canonical[key] = value;
      point.overrides.push_back({key, std::move(value)});
    }
    if (auto [first, inserted] = names.emplace(point.label, i); !inserted) {
      error(v, path,
            path + ": the name '" + point.label + "' is already used by variants[" +
                std::to_string(first->second) + "]");
      continue;
    }
    if (auto [first, inserted] = contents.emplace(canonical.dump(), i); !inserted) {
      error(v, path,
            path + ": sets the same keys to the same values as variants[" +
                std::to_string(first->second) + "] (the runs would be identical)");
      continue;
    }
    axis.points.push_back(std::move(point));
  }
  def_.parameters.push_back("variant");
  for (const auto& k : axis.keys)
    def_.parameters.push_back(k);
  def_.axes.push_back(std::move(axis));
}

void SweepParser::check_run_count(const YAML::Node& root) {
  std::uint64_t runs = def_.seeds.size();
  std::string factors;
  bool overflow = false;
  for (const SweepAxis& axis : def_.axes) {
    const std::uint64_t n = axis.points.size();
    if (n != 0 && runs > std::numeric_limits<std::uint64_t>::max() / n)
      overflow = true;
    else
      runs *= n;
    factors += std::to_string(n) + " " + (axis.name == "variant" ? "variants" : axis.name) + " × ";
  }
  if (!overflow && runs <= kMaxSweepRuns) return;
  const YAML::Node vary = child(root, "vary");
  const YAML::Node seeds = child(root, "seeds");
  const YAML::Node at = vary.IsDefined() ? vary : seeds.IsDefined() ? seeds : root;
  error(at, "vary",
        "the sweep would have " +
            (overflow ? std::string("more than 1.8e+19") : std::to_string(runs)) + " runs (" +
            factors + std::to_string(def_.seeds.size()) + " seeds), more than the limit of " +
            std::to_string(kMaxSweepRuns) + " (docs/sweeps.md, \"Limits\")");
}

// Loads the base once alone (its own errors are the sweep's) and once per variant with every
// override (only unknown keys are the sweep's: bad values just make those runs fail).
void SweepParser::probe() {
  // Probes check keys and values, not layouts: the sensors are counted, not built.
  LoadOptions options;
  options.build_sensors = false;
  const LoadResult alone =
      load_scenario_text(def_.base_text, def_.base_path, {}, std::nullopt, options);
  for (const Diagnostic& d : alone.diagnostics)
    reader_.error(d.location, "in the base scenario: " + d.message);
  if (!alone.diagnostics.empty()) return;
  std::size_t probes = def_.axes.empty() ? 1 : def_.axes.front().points.size();
  const bool variants = !def_.axes.empty() && def_.axes.front().name == "variant";
  if (!variants) probes = 1;
  std::set<std::string> reported;
  for (std::size_t p = 0; p < probes; ++p) {
    std::vector<std::string> overrides;
    for (const auto& o : def_.set)
      overrides.push_back(o.key + "=" + o.value.dump());
    for (std::size_t a = 0; a < def_.axes.size(); ++a) {
      const AxisPoint& point = def_.axes[a].points[a == 0 && variants ? p : 0];
      for (const auto& o : point.overrides)
        overrides.push_back(o.key + "=" + o.value.dump());
    }
    const LoadResult loaded =
        load_scenario_text(def_.base_text, def_.base_path, overrides, std::nullopt, options);
    for (const Diagnostic& d : loaded.diagnostics) {
      if (d.location.rfind("--set ", 0) != 0) continue;
      const bool structural = d.message.rfind("unknown key", 0) == 0 ||
                              d.message.find("is not a section") != std::string::npos ||
                              d.message.rfind("empty key", 0) == 0;
      if (!structural) continue;
      const std::string text = d.location.substr(6);
      const std::string key = text.substr(0, text.find('='));
      if (!reported.insert(key + d.message).second) continue;
      auto where = key_location_.find(key);
      reader_.error(where != key_location_.end() ? where->second : file_ + ":1:1",
                    "'" + key + "' is not a key of the base scenario: " + d.message);
    }
  }
}

SweepLoad SweepParser::parse(const std::string& text) {
  SweepLoad result;
  // UTF-8, one document, no tags, bounded aliases: the same checks as a scenario's text.
  result.diagnostics = check_yaml_text(text, file_);
  if (!result.diagnostics.empty()) return result;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    result.diagnostics.push_back(
        {file_ + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1),
         "YAML syntax error: " + shown_text(e.msg)});
    return result;
  }
  if (!root.IsMap()) {
    result.diagnostics.push_back(
        {file_ + ":1:1", "a sweep file is a mapping with at least 'base' (see docs/sweeps.md)"});
    return result;
  }
  def_.file = file_;
  def_.text = text;
  check_top_keys(root);

  const YAML::Node base = child(root, "base");
  if (!base.IsDefined() || !base.IsScalar() || base.Scalar().empty()) {
    error(base.IsDefined() ? base : root, "base",
          "base: missing or not a file name (the scenario every run starts from, relative to the "
          "sweep file)");
  } else {
    const fs::path path = (fs::path(file_).parent_path() / base.Scalar()).lexically_normal();
    std::string problem;
    def_.base_path = path.string();
    if (!read_regular_file(def_.base_path, kMaxScenarioFileBytes, def_.base_text, problem)) {
      error(
          base, "base",
          "base: cannot read the scenario '" + shown_text(def_.base_path) + "' (" + problem + ")");
    } else if (auto problems = check_yaml_text(def_.base_text, def_.base_path); !problems.empty()) {
      // Checked before the canonical form below walks it (an alias bomb would).
      for (const Diagnostic& d : problems)
        reader_.error(d.location, "in the base scenario: " + d.message);
      def_.base_text.clear();
    }
    std::string canonical = def_.base_text;
    try {
      YAML::Emitter out;
      out << YAML::Load(def_.base_text);
      canonical = out.c_str();
    } catch (const YAML::Exception&) {
    }
    def_.base_key = hex16(fnv1a64(canonical));
  }
  read_seeds(child(root, "seeds"));
  read_set(child(root, "set"));
  read_variants(child(root, "variants"));
  read_vary_and_zip(child(root, "vary"), child(root, "zip"));
  read_report(child(root, "report"));
  for (const char* text_key : {"name", "description"}) {
    const YAML::Node n = child(root, text_key);
    if (n.IsDefined() && !n.IsScalar())
      error(n, text_key, std::string(text_key) + ": expected a text");
  }

  Section output(reader_, child(root, "output"), "output", "/output");
  def_.output_dir =
      output.text("dir", "runs/sweep-" + sanitized_name(fs::path(file_).stem().string()));
  def_.keep_runs = output.boolean("keep_runs", false);
  output.finish();

  // Parameter columns must be distinct once sanitised.
  std::map<std::string, std::string> columns;
  for (const auto& p : def_.parameters) {
    auto [it, inserted] = columns.emplace(sanitize_column("p_" + p), p);
    if (!inserted && it->second != p) {
      auto where = key_location_.find(p);
      reader_.error(where != key_location_.end() ? where->second : file_ + ":1:1",
                    "'" + p + "' and '" + it->second + "' would share the column " + it->first);
    }
  }
  // Remove duplicates (a variant key repeated): keep the first.
  std::vector<std::string> unique;
  for (const auto& p : def_.parameters)
    if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
  def_.parameters = unique;

  check_run_count(root);
  if (reader_.ok() && !def_.base_text.empty()) probe();
  if (!reader_.ok()) {
    result.diagnostics = reader_.diagnostics();
    return result;
  }
  // A safety net behind the checks above: two runs with one id would overwrite each other.
  std::map<std::string, std::size_t> ids;
  for (const RunSpec& r : expand_sweep(def_))
    if (auto [it, inserted] = ids.emplace(r.id, r.index); !inserted) {
      result.diagnostics.push_back({file_ + ":1:1", "runs " + std::to_string(it->second) + " and " +
                                                        std::to_string(r.index) + " (" + r.label +
                                                        ") are the same run"});
      return result;
    }
  result.sweep = std::move(def_);
  return result;
}

}  // namespace masnet::scenarios::sweep_parsing

namespace masnet::scenarios {

SweepLoad load_sweep_text(const std::string& text, const std::string& file_name) {
  sweep_parsing::SweepParser parser(file_name);
  return parser.parse(text);
}

SweepLoad load_sweep(const std::string& path) {
  std::string text, problem;
  if (!read_regular_file(path, kMaxScenarioFileBytes, text, problem)) {
    SweepLoad result;
    result.diagnostics.push_back({path + ":1:1", "cannot read the sweep file (" + problem + ")"});
    return result;
  }
  return load_sweep_text(text, path);
}

}  // namespace masnet::scenarios
