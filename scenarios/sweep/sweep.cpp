#include "scenarios/sweep/sweep.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <ctime>
#include <deque>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <sqlite3.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>
#include <boost/asio/post.hpp>
#include <boost/asio/thread_pool.hpp>

#include "scenarios/loader/input.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/report/figures.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/run/sensors_csv.hpp"
#include "scenarios/sweep/sweep_report.hpp"
#include "scenarios/sweep/sweep_statistics.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ---- Small helpers -----------------------------------------------------------------------------

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  // splitmix64's finaliser: FNV alone leaves ids of neighbouring seeds looking alike.
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 31;
  return h;
}

std::string hex16(std::uint64_t h) {
  return fmt::format("{:016x}", h);
}

// A YAML value as JSON: plain scalars become integers, numbers or booleans when they read as
// such, quoted scalars stay texts. JSON is YAML, so value.dump() is a valid --set VALUE.
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

// Decimals a number is written with: "0.25" -> 2, "1e-3" -> 3, "5" -> 0.
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

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// ---- Reading a sweep file ----------------------------------------------------------------------

// Each run's seed comes from `seeds` and replaces the scenario's `seed` after every override.
constexpr const char* kSeedKey =
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
  // The number of runs, from the axes' sizes, before anything is expanded.
  void check_run_count(const YAML::Node& root);
  void probe();

  ScenarioReader reader_;
  std::string file_;
  SweepDef def_;
  // Where each override key is first given in the sweep file, for probe errors.
  std::map<std::string, std::string> key_location_;
};

void SweepParser::check_top_keys(const YAML::Node& root) {
  static const std::vector<std::string> known = {"name",     "description", "base", "seeds", "set",
                                                 "variants", "vary",        "zip",  "output"};
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
                          "variants, vary, zip, output, name, description)";
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

std::optional<std::vector<json>> SweepParser::read_values(const std::string& key,
                                                          const YAML::Node& node) {
  const std::string path = "vary." + key;
  if (node.IsSequence()) {
    if (node.size() == 0) {
      error(node, path, path + ": the list of values is empty");
      return std::nullopt;
    }
    std::vector<json> values;
    std::set<std::string> seen;
    bool ok = true;
    for (std::size_t i = 0; i < node.size(); ++i) {
      json v = yaml_to_json(node[i]);
      if (!seen.insert(v.dump()).second) {
        error(node[i], path, path + ": the value " + v.dump() + " is listed twice");
        ok = false;
      }
      values.push_back(std::move(v));
    }
    if (!ok) return std::nullopt;
    return values;
  }
  if (node.IsMap()) {
    std::map<std::string, YAML::Node> parts;
    bool ok = true;
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string k = it->first.IsScalar() ? it->first.Scalar() : "?";
      if (k != "from" && k != "to" && k != "step") {
        std::string message =
            path + ": unknown key '" + k + "' in a range (expected from, to, step)";
        if (auto guess = closest(k, {"from", "to", "step"}))
          message += " (did you mean '" + *guess + "'?)";
        error(it->first, path, message);
        ok = false;
        continue;
      }
      parts[k] = it->second;
    }
    double number[3] = {0, 0, 0};
    bool integers = true;
    int decimals = 0;
    const char* names[3] = {"from", "to", "step"};
    for (int i = 0; i < 3; ++i) {
      auto found = parts.find(names[i]);
      if (found == parts.end()) {
        error(node, path,
              path + ": a range needs 'from', 'to' and 'step' (missing '" + std::string(names[i]) +
                  "')");
        ok = false;
        continue;
      }
      const YAML::Node& n = found->second;
      if (!n.IsScalar() || !YAML::convert<double>::decode(n, number[i]) ||
          !std::isfinite(number[i])) {
        error(n, path, path + "." + names[i] + ": expected a number");
        ok = false;
        continue;
      }
      long long whole = 0;
      if (!YAML::convert<long long>::decode(n, whole)) integers = false;
      decimals = std::max(decimals, written_decimals(n.Scalar()));
    }
    if (!ok) return std::nullopt;
    const auto& [from, to, step] = number;
    std::vector<json> values = sweep_range(from, to, step, decimals, integers);
    if (values.empty()) {
      error(parts["step"], path,
            path + ".step: must be non-zero and go from 'from' towards 'to' (from " +
                fmt::format("{}", from) + " to " + fmt::format("{}", to) + " by " +
                fmt::format("{}", step) + ")");
      return std::nullopt;
    }
    if (values.size() > 100000) {
      error(node, path,
            path + ": the range has " + std::to_string(values.size()) + " values (at most 100000)");
      return std::nullopt;
    }
    return values;
  }
  error(node, path,
        path +
            ": expected a list of values, e.g. [0, 0.1, 0.2], or a range {from: 0, to: 0.5, step: "
            "0.1}");
  return std::nullopt;
}

void SweepParser::read_vary_and_zip(const YAML::Node& vary, const YAML::Node& zip) {
  std::vector<std::string> keys;
  std::map<std::string, std::vector<json>> values;
  std::map<std::string, YAML::Node> key_nodes;
  if (vary.IsDefined() && !vary.IsNull()) {
    if (!vary.IsMap()) {
      error(vary, "vary", "vary: expected a mapping of scenario keys to lists of values or ranges");
      return;
    }
    std::set<std::string> set_keys, variant_keys;
    for (const auto& o : def_.set)
      set_keys.insert(o.key);
    if (!def_.axes.empty())
      variant_keys.insert(def_.axes.front().keys.begin(), def_.axes.front().keys.end());
    for (auto it = vary.begin(); it != vary.end(); ++it) {
      const std::string key = it->first.IsScalar() ? it->first.Scalar() : "?";
      if (!valid_key(key)) {
        error(it->first, "vary",
              "vary: '" + key + "' is not a dotted scenario key like radio.loss");
        continue;
      }
      if (key == "seed") {
        error(it->first, "vary", kSeedKey);
        continue;
      }
      if (key_nodes.count(key)) {
        error(it->first, "vary", "vary: '" + key + "' is given twice");
        continue;
      }
      if (set_keys.count(key)) {
        error(it->first, "vary",
              "vary: '" + key + "' is also fixed under 'set'; give it in one place");
        continue;
      }
      if (variant_keys.count(key)) {
        error(it->first, "vary",
              "vary: '" + key + "' is also set by the variants; give it in one place");
        continue;
      }
      key_location_.emplace(key, at(it->first, "vary"));
      key_nodes[key] = it->first;
      if (auto v = read_values(key, it->second)) {
        keys.push_back(key);
        values[key] = std::move(*v);
      }
    }
  }
  // Zip groups: keys of `vary` whose lists are walked together.
  std::map<std::string, std::size_t> group_of;
  std::vector<std::vector<std::string>> groups;
  if (zip.IsDefined() && !zip.IsNull()) {
    if (!zip.IsSequence()) {
      error(zip, "zip",
            "zip: expected a list of key groups, e.g. [[protocol.decay.patience, "
            "protocol.decay.step]]");
    } else {
      for (std::size_t g = 0; g < zip.size(); ++g) {
        const YAML::Node group = zip[g];
        const std::string path = "zip[" + std::to_string(g) + "]";
        if (!group.IsSequence() || group.size() < 2) {
          error(group, path, path + ": expected a list of at least two keys of 'vary'");
          continue;
        }
        std::vector<std::string> members;
        bool ok = true;
        for (std::size_t i = 0; i < group.size(); ++i) {
          const std::string key = group[i].IsScalar() ? group[i].Scalar() : "?";
          if (!key_nodes.count(key)) {
            error(group[i], path, path + ": '" + key + "' is not a key of 'vary'");
            ok = false;
          } else if (group_of.count(key) ||
                     std::find(members.begin(), members.end(), key) != members.end()) {
            error(group[i], path, path + ": '" + key + "' is already in a zip group");
            ok = false;
          } else if (values.count(key)) {
            members.push_back(key);
          } else {
            ok = false;  // its values were bad: reported already
          }
        }
        if (!ok) continue;
        const std::size_t n = values[members.front()].size();
        for (const auto& key : members)
          if (values[key].size() != n) {
            error(group, path,
                  path + ": keys zipped together need lists of the same length, but '" +
                      members.front() + "' has " + std::to_string(n) + " values and '" + key +
                      "' has " + std::to_string(values[key].size()));
            ok = false;
            break;
          }
        if (!ok) continue;
        for (const auto& key : members)
          group_of[key] = groups.size();
        groups.push_back(members);
      }
    }
  }
  // Axes in the order of `vary`; a zip group sits where its first key is.
  std::set<std::size_t> placed;
  for (const auto& key : keys) {
    SweepAxis axis;
    std::vector<std::string> members = {key};
    if (auto g = group_of.find(key); g != group_of.end()) {
      if (!placed.insert(g->second).second) continue;
      members = groups[g->second];
    }
    axis.name = members.front();
    axis.keys = members;
    axis.numeric = true;
    const std::size_t n = values[members.front()].size();
    for (std::size_t i = 0; i < n; ++i) {
      AxisPoint point;
      std::string label;
      for (const auto& m : members) {
        const json& v = values[m][i];
        label += (label.empty() ? "" : ", ") + value_label(v);
        point.overrides.push_back({m, v});
      }
      point.label = members.size() > 1 ? "(" + label + ")" : label;
      if (!values[members.front()][i].is_number()) axis.numeric = false;
      axis.points.push_back(std::move(point));
    }
    for (const auto& m : members)
      def_.parameters.push_back(m);
    def_.axes.push_back(std::move(axis));
  }
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

}  // namespace

// ---- Expansion ---------------------------------------------------------------------------------

std::vector<json> sweep_range(double from, double to, double step, int decimals, bool integers) {
  std::vector<json> values;
  if (step == 0.0 || !std::isfinite(step) || (to - from) * step < 0) return values;
  const double span = (to - from) / step;
  if (span > 1e7) return std::vector<json>(100001);  // too many: the caller says so
  // Inclusive of `to` despite rounding: 0 to 0.5 by 0.1 is six values, never five.
  const auto count = static_cast<std::int64_t>(std::floor(span + 1e-9)) + 1;
  const double scale = std::pow(10.0, std::clamp(decimals, 0, 15));
  for (std::int64_t k = 0; k < count; ++k) {
    if (integers) {
      values.emplace_back(std::llround(from) + k * std::llround(step));
    } else {
      const double v = std::round((from + static_cast<double>(k) * step) * scale) / scale;
      values.emplace_back(v == 0.0 ? 0.0 : v);  // no -0
    }
  }
  return values;
}

std::string sweep_run_id(const std::string& base_key, const std::vector<SweepOverride>& overrides,
                         std::uint64_t seed) {
  json effective = json::object();
  for (const auto& o : overrides)
    effective[o.key] = o.value;
  const json canonical = {{"base", base_key}, {"overrides", effective}, {"seed", seed}};
  return hex16(fnv1a64(canonical.dump()));
}

std::vector<RunSpec> expand_sweep(const SweepDef& sweep) {
  std::vector<RunSpec> runs;
  std::vector<std::size_t> points(sweep.axes.size(), 0);
  for (const auto& axis : sweep.axes)
    if (axis.points.empty()) return runs;
  for (;;) {
    std::vector<SweepOverride> overrides = sweep.set;
    json parameters = json::object();
    std::string label;
    for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
      const SweepAxis& axis = sweep.axes[a];
      const AxisPoint& point = axis.points[points[a]];
      if (axis.name == "variant") {
        parameters["variant"] = point.label;
        label += "variant=" + point.label + " ";
      }
      for (const auto& o : point.overrides) {
        overrides.push_back(o);
        parameters[o.key] = o.value;
        if (axis.name != "variant") label += o.key + "=" + value_label(o.value) + " ";
      }
    }
    for (std::uint64_t seed : sweep.seeds) {
      RunSpec r;
      r.index = runs.size();
      r.seed = seed;
      r.points = points;
      r.id = sweep_run_id(sweep.base_key, overrides, seed);
      for (const auto& o : overrides)
        r.overrides.push_back(o.key + "=" + o.value.dump());
      r.parameters = parameters;
      r.label = label + "seed=" + std::to_string(seed);
      runs.push_back(std::move(r));
    }
    // Odometer: the last axis turns fastest.
    std::size_t a = sweep.axes.size();
    while (a > 0) {
      --a;
      if (++points[a] < sweep.axes[a].points.size()) break;
      points[a] = 0;
      if (a == 0) return runs;
    }
    if (sweep.axes.empty()) return runs;
  }
}

SweepLoad load_sweep_text(const std::string& text, const std::string& file_name) {
  SweepParser parser(file_name);
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

// ---- Executing runs ----------------------------------------------------------------------------

json RunResult::to_json() const {
  return {{"index", index}, {"id", id}, {"ok", ok}, {"error", error}, {"summary", summary}};
}

RunResult RunResult::from_json(const json& j) {
  RunResult r;
  r.index = j.at("index").get<std::size_t>();
  r.id = j.at("id").get<std::string>();
  r.ok = j.at("ok").get<bool>();
  r.error = j.at("error").get<std::string>();
  r.summary = j.at("summary");
  return r;
}

RunResult execute_sweep_run(const SweepDef& sweep, const RunSpec& run, const std::string& out_dir) {
  RunResult result;
  result.index = run.index;
  result.id = run.id;
  try {
    LoadResult loaded = load_scenario(sweep.base_path, run.overrides, run.seed);
    if (!loaded.scenario) {
      for (const Diagnostic& d : loaded.diagnostics)
        result.error += (result.error.empty() ? "" : "\n") + d.text();
      return result;
    }
    const ScenarioDef& def = *loaded.scenario;
    Run simulation(def);
    simulation.execute();
    result.summary = simulation.summary();
    if (sweep.keep_runs) {
      publish_run_directory((fs::path(out_dir) / "runs" / run.id).string(),
                            [&](const std::string& dir) {
                              simulation.write_files(dir);
                              write_sensors_csv(fs::path(dir) / "sensors.csv", def.world.sensors);
                            });
    }
    // The resolved scenario is (base, overrides, seed) again: not worth a copy per row.
    if (result.summary.contains("scenario")) result.summary["scenario"].erase("resolved");
    result.ok = true;
  } catch (const OutputError& e) {
    result.ok = false;
    result.summary = nullptr;
    result.error = e.what();
  } catch (const std::exception& e) {
    result.ok = false;
    result.summary = nullptr;
    result.error = std::string("internal error: ") + e.what();
  }
  return result;
}

struct SweepWorkers::Shared {
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<RunResult> done;
  // Last member: destroyed (stopped and joined) first, while the queue still exists.
  boost::asio::thread_pool pool;
  explicit Shared(std::size_t threads) : pool(threads) {}
  ~Shared() {
    pool.stop();  // on an early exit, queued runs are dropped; running ones finish
    pool.join();
  }
};

SweepWorkers::SweepWorkers(const SweepDef& sweep, const std::vector<RunSpec>& runs,
                           std::string out_dir, int threads)
    : sweep_(sweep),
      runs_(runs),
      out_dir_(std::move(out_dir)),
      shared_(std::make_unique<Shared>(static_cast<std::size_t>(std::max(1, threads)))) {}

SweepWorkers::~SweepWorkers() = default;

void SweepWorkers::submit(std::size_t index) {
  ++in_flight_;
  Shared* shared = shared_.get();
  boost::asio::post(shared->pool, [this, shared, index] {
    RunResult r = execute_sweep_run(sweep_, runs_.at(index), out_dir_);
    {
      std::lock_guard<std::mutex> lock(shared->mutex);
      shared->done.push_back(std::move(r));
    }
    shared->ready.notify_one();
  });
}

std::optional<RunResult> SweepWorkers::next(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(shared_->mutex);
  if (!shared_->ready.wait_for(lock, timeout, [&] { return !shared_->done.empty(); }))
    return std::nullopt;
  RunResult r = std::move(shared_->done.front());
  shared_->done.pop_front();
  --in_flight_;
  return r;
}

// ---- Results -----------------------------------------------------------------------------------

namespace {
void flatten_into(const json& j, const std::string& prefix,
                  std::vector<std::pair<std::string, double>>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
      if (key == "scenario.resolved" || key == "seed") continue;
      flatten_into(it.value(), key, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      flatten_into(j[i], prefix + "." + std::to_string(i), out);
  } else if (j.is_boolean()) {
    out.emplace_back(prefix, j.get<bool>() ? 1.0 : 0.0);
  } else if (j.is_number()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) out.emplace_back(prefix, v);
  }
}
}  // namespace

std::vector<std::pair<std::string, double>> flatten_metrics(const json& summary) {
  std::vector<std::pair<std::string, double>> out;
  flatten_into(summary, "", out);
  return out;
}

std::string sanitize_column(const std::string& key) {
  std::string c;
  for (char ch : key) {
    const auto u = static_cast<unsigned char>(ch);
    c += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '_';
  }
  if (c.empty() || std::isdigit(static_cast<unsigned char>(c.front()))) c = "_" + c;
  return c;
}

namespace {

// The fixed columns of `runs`, in order; then p_<parameter>, then one per metric.
const std::vector<std::string> kFixedColumns = {"run_id",     "run_index",   "seed",
                                                "status",     "error",       "label",
                                                "parameters", "fingerprint", "finished_at"};

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db) +
                               " in: " + sql);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  void bind(int i, const std::string& s) {
    sqlite3_bind_text(stmt_, i, s.c_str(), -1, SQLITE_TRANSIENT);
  }
  void bind(int i, double v) { sqlite3_bind_double(stmt_, i, v); }
  void bind(int i, std::int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
  void bind_null(int i) { sqlite3_bind_null(stmt_, i); }
  void bind(int i, const json& v) {
    if (v.is_null())
      bind_null(i);
    else if (v.is_string())
      bind(i, v.get<std::string>());
    else if (v.is_boolean())
      bind(i, std::int64_t{v.get<bool>() ? 1 : 0});
    else if (v.is_number_integer())
      bind(i, v.get<std::int64_t>());
    else if (v.is_number())
      bind(i, v.get<double>());
    else
      bind(i, v.dump());
  }
  /// True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db_));
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::string text(int i) const {
    const unsigned char* t = sqlite3_column_text(stmt_, i);
    return t ? reinterpret_cast<const char*>(t) : std::string();
  }
  double number(int i) const { return sqlite3_column_double(stmt_, i); }
  bool is_null(int i) const { return sqlite3_column_type(stmt_, i) == SQLITE_NULL; }
  sqlite3_stmt* get() const { return stmt_; }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

struct SweepSession::Db {
  sqlite3* db = nullptr;
  std::int64_t invocation = 0;
  std::set<std::string> columns;                        // of `runs`
  std::map<std::string, std::string> column_of_metric;  // dotted key -> column
  ~Db() {
    if (db) sqlite3_close(db);
  }
  void exec(const std::string& sql) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string m = message ? message : "unknown error";
      sqlite3_free(message);
      throw std::runtime_error("results.sqlite: " + m + " in: " + sql);
    }
  }
  void add_column(const std::string& name) {
    if (columns.count(name)) return;
    exec("ALTER TABLE runs ADD COLUMN \"" + name + "\"");
    columns.insert(name);
  }
};

SweepSession::SweepSession(const SweepDef& sweep, std::vector<RunSpec> runs, SweepOptions options)
    : sweep_(sweep),
      runs_(std::move(runs)),
      options_(std::move(options)),
      db_(std::make_unique<Db>()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  const fs::path out(options_.out_dir);
  const fs::path db_path = out / "results.sqlite";
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw SweepOutputError("'" + out.string() + "' exists and is not a directory");
  // --force discards a sweep's own results only: a folder of other files is never emptied.
  if (fs::exists(out, ec) && !fs::is_empty(out, ec) && !fs::exists(db_path, ec)) {
    throw SweepOutputError("refusing to write into '" + out.string() +
                           "': it is not empty and holds no sweep results (results.sqlite); "
                           "choose another --out");
  }
  if (options_.force) {
    for (const char* name : {"results.sqlite", "results.sqlite-journal", "results.sqlite-wal",
                             "results.sqlite-shm", "results.csv", "report.html"})
      fs::remove(out / name, ec);
    fs::remove_all(out / "runs", ec);
  }
  fs::create_directories(out);
  if (sqlite3_open_v2(db_path.c_str(), &db_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK)
    throw SweepOutputError("cannot open '" + db_path.string() + "': " + sqlite3_errmsg(db_->db));
  sqlite3_busy_timeout(db_->db, 5000);
  try {
    db_->exec(
        "CREATE TABLE IF NOT EXISTS sweep (invocation INTEGER PRIMARY KEY, started_at TEXT, "
        "finished_at TEXT, sweep_file TEXT, sweep_text TEXT, base_file TEXT, base_text TEXT, "
        "masnet_version TEXT, jobs INTEGER, ranks INTEGER, runs_total INTEGER, runs_skipped "
        "INTEGER, runs_executed INTEGER, runs_failed INTEGER, wall_time_s REAL)");
    db_->exec(
        "CREATE TABLE IF NOT EXISTS runs (run_id TEXT PRIMARY KEY, run_index INTEGER, seed "
        "INTEGER, "
        "status TEXT, error TEXT, label TEXT, parameters TEXT, fingerprint TEXT, finished_at "
        "TEXT)");
    db_->exec(
        "CREATE TABLE IF NOT EXISTS metrics (run_id TEXT, key TEXT, value REAL, "
        "PRIMARY KEY (run_id, key)) WITHOUT ROWID");
  } catch (const std::runtime_error& e) {
    throw SweepOutputError("'" + db_path.string() + "' is not a sweep database: " + e.what());
  }
  {
    Statement info(db_->db, "PRAGMA table_info(runs)");
    while (info.step())
      db_->columns.insert(info.text(1));
  }
  for (const auto& c : kFixedColumns)
    if (!db_->columns.count(c))
      throw SweepOutputError("'" + db_path.string() + "' is not a sweep database (no column " + c +
                             ")");

  db_->exec("BEGIN");
  for (const auto& p : sweep_.parameters)
    db_->add_column(sanitize_column("p_" + p));
  {
    Statement insert(db_->db,
                     "INSERT INTO sweep (started_at, sweep_file, sweep_text, base_file, base_text, "
                     "masnet_version, jobs, ranks, runs_total) VALUES (?,?,?,?,?,?,?,?,?)");
    insert.bind(1, now_utc());
    insert.bind(2, sweep_.file);
    insert.bind(3, sweep_.text);
    insert.bind(4, sweep_.base_path);
    insert.bind(5, sweep_.base_text);
    insert.bind(6, std::string(MASNET_VERSION));
    insert.bind(7, std::int64_t{options_.jobs});
    insert.bind(8, std::int64_t{options_.ranks});
    insert.bind(9, static_cast<std::int64_t>(runs_.size()));
    insert.step();
    db_->invocation = sqlite3_last_insert_rowid(db_->db);
  }
  // Finished runs are skipped, failed ones retried; rows of no current run lose their index.
  std::map<std::string, std::string> status;
  {
    Statement rows(db_->db, "SELECT run_id, status FROM runs");
    while (rows.step())
      status[rows.text(0)] = rows.text(1);
  }
  db_->exec("UPDATE runs SET run_index = NULL");
  Statement index(db_->db, "UPDATE runs SET run_index = ?, label = ? WHERE run_id = ?");
  std::set<std::string> current;
  for (const RunSpec& r : runs_) {
    current.insert(r.id);
    auto found = status.find(r.id);
    if (found != status.end()) {
      index.bind(1, static_cast<std::int64_t>(r.index));
      index.bind(2, r.label);
      index.bind(3, r.id);
      index.step();
      index.reset();
    }
    if (found != status.end() && found->second == "ok")
      ++counts_.skipped;
    else
      pending_.push_back(r.index);
  }
  for (const auto& [id, s] : status)
    counts_.foreign += current.count(id) ? 0 : 1;
  db_->exec("COMMIT");
  counts_.total = runs_.size();
}

SweepSession::~SweepSession() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void SweepSession::record(const RunResult& result) {
  const RunSpec& spec = runs_.at(result.index);
  const auto metrics =
      result.ok ? flatten_metrics(result.summary) : std::vector<std::pair<std::string, double>>{};
  db_->exec("BEGIN");
  try {
    std::vector<std::string> names = kFixedColumns;
    std::vector<json> values = {
        spec.id,
        static_cast<std::int64_t>(spec.index),
        static_cast<std::int64_t>(spec.seed),
        result.ok ? "ok" : "failed",
        result.ok ? json(nullptr) : json(result.error),
        spec.label,
        spec.parameters.dump(),
        result.ok ? result.summary.value("fingerprint", json(nullptr)) : json(nullptr),
        now_utc()};
    for (const auto& p : sweep_.parameters) {
      names.push_back(sanitize_column("p_" + p));
      values.push_back(spec.parameters.contains(p) ? spec.parameters[p] : json(nullptr));
    }
    std::set<std::string> used(names.begin(), names.end());
    for (const auto& [key, value] : metrics) {
      auto column = db_->column_of_metric.find(key);
      if (column == db_->column_of_metric.end()) {
        std::string name = sanitize_column(key);
        if (std::find(kFixedColumns.begin(), kFixedColumns.end(), name) != kFixedColumns.end() ||
            name.rfind("p_", 0) == 0)
          name = "m_" + name;
        column = db_->column_of_metric.emplace(key, name).first;
      }
      if (!used.insert(column->second).second) continue;  // two keys, one column: keep the first
      db_->add_column(column->second);
      names.push_back(column->second);
      // Counts stay integers in SQL (and in results.csv).
      if (value == std::floor(value) && std::abs(value) < 9e15)
        values.emplace_back(static_cast<std::int64_t>(value));
      else
        values.emplace_back(value);
    }
    std::string sql = "INSERT OR REPLACE INTO runs (", marks;
    for (std::size_t i = 0; i < names.size(); ++i) {
      sql += (i ? ",\"" : "\"") + names[i] + "\"";
      marks += i ? ",?" : "?";
    }
    sql += ") VALUES (" + marks + ")";
    Statement insert(db_->db, sql);
    for (std::size_t i = 0; i < values.size(); ++i)
      insert.bind(static_cast<int>(i + 1), values[i]);
    insert.step();
    Statement clear(db_->db, "DELETE FROM metrics WHERE run_id = ?");
    clear.bind(1, spec.id);
    clear.step();
    Statement metric(db_->db, "INSERT INTO metrics (run_id, key, value) VALUES (?,?,?)");
    for (const auto& [key, value] : metrics) {
      metric.bind(1, spec.id);
      metric.bind(2, key);
      metric.bind(3, value);
      metric.step();
      metric.reset();
    }
    db_->exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_->db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  ++counts_.executed;
  if (!result.ok) ++counts_.failed;
  draw_progress(false);
}

void SweepSession::draw_progress(bool final) {
  if (!options_.progress) return;
  const auto now = std::chrono::steady_clock::now();
  if (!final && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::size_t todo = pending_.size();
  const std::size_t done = counts_.executed;
  const double eta =
      done > 0 ? elapsed * static_cast<double>(todo - done) / static_cast<double>(done) : 0.0;
  auto clock = [](double s) {
    const auto t = static_cast<long long>(std::llround(s));
    return fmt::format("{}:{:02d}", t / 60, t % 60);
  };
  std::string line = fmt::format("sweep: {}/{} runs", done, todo);
  if (counts_.skipped) line += fmt::format(" ({} done before)", counts_.skipped);
  if (counts_.failed) line += fmt::format(", {} failed", counts_.failed);
  line += ", " + clock(elapsed) + " elapsed";
  if (done > 0 && done < todo) line += ", ETA " + clock(eta);
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

SweepCounts SweepSession::finish() {
  if (drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
  }
  counts_.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  {
    Statement update(
        db_->db,
        "UPDATE sweep SET finished_at = ?, runs_skipped = ?, runs_executed = ?, runs_failed = ?, "
        "wall_time_s = ? WHERE invocation = ?");
    update.bind(1, now_utc());
    update.bind(2, static_cast<std::int64_t>(counts_.skipped));
    update.bind(3, static_cast<std::int64_t>(counts_.executed));
    update.bind(4, static_cast<std::int64_t>(counts_.failed));
    update.bind(5, counts_.wall_time_s);
    update.bind(6, db_->invocation);
    update.step();
  }
  const fs::path out(options_.out_dir);
  std::error_code ec;
  write_statistics_table(db_->db, runs_);

  // results.csv: the rows of this sweep's runs, columns fixed, parameters, metrics by name.
  {
    Statement rows(db_->db, "SELECT * FROM runs WHERE run_index IS NOT NULL ORDER BY run_index");
    const int n = sqlite3_column_count(rows.get());
    std::vector<std::string> names;
    for (int i = 0; i < n; ++i)
      names.emplace_back(sqlite3_column_name(rows.get(), i));
    std::vector<int> order;
    auto position = [&](const std::string& name) {
      return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    for (const auto& c : kFixedColumns)
      order.push_back(position(c));
    for (const auto& p : sweep_.parameters)
      order.push_back(position(sanitize_column("p_" + p)));
    std::vector<std::string> rest;
    for (const auto& name : names)
      if (std::find(kFixedColumns.begin(), kFixedColumns.end(), name) == kFixedColumns.end() &&
          name.rfind("p_", 0) != 0)
        rest.push_back(name);
    std::sort(rest.begin(), rest.end());
    for (const auto& name : rest)
      order.push_back(position(name));
    // Parameter columns of an earlier version of the sweep file are kept after the metrics.
    for (const auto& name : names)
      if (name.rfind("p_", 0) == 0 &&
          std::find(order.begin(), order.end(), position(name)) == order.end())
        order.push_back(position(name));
    const fs::path tmp = out / "results.csv.partial";
    try {
      OutputFile csv(tmp);
      for (std::size_t i = 0; i < order.size(); ++i)
        csv.print("{}{}", i ? "," : "", names[order[i]]);
      csv.write("\n");
      while (rows.step()) {
        for (std::size_t i = 0; i < order.size(); ++i) {
          const int c = order[i];
          if (i) csv.write(",");
          switch (sqlite3_column_type(rows.get(), c)) {
            case SQLITE_NULL:
              break;
            case SQLITE_INTEGER:
              csv.print("{}", sqlite3_column_int64(rows.get(), c));
              break;
            case SQLITE_FLOAT:
              csv.write(shortest(rows.number(c)));
              break;
            default:
              csv.write(csv_cell(rows.text(c)));
          }
        }
        csv.write("\n");
      }
      csv.close();
    } catch (...) {
      fs::remove(tmp, ec);
      throw;
    }
    fs::rename(tmp, out / "results.csv");
  }

  // report.html: configurations over seeds, from the database (runs of earlier invocations too).
  SweepReportInput report;
  report.title = fs::path(sweep_.file).stem().string();
  report.sweep_file = sweep_.file;
  report.base_file = sweep_.base_path;
  report.seeds = sweep_.seeds.size();
  for (const auto& axis : sweep_.axes) {
    SweepReportAxis a;
    a.name = axis.name;
    a.numeric = axis.numeric;
    for (const auto& p : axis.points) {
      a.labels.push_back(p.label);
      a.x.push_back(axis.numeric && !p.overrides.empty() ? p.overrides.front().value.get<double>()
                                                         : 0.0);
    }
    report.axes.push_back(std::move(a));
  }
  {
    std::map<std::string, std::pair<std::string, std::string>> rows;  // id -> status, error
    Statement s(db_->db, "SELECT run_id, status, error FROM runs WHERE run_index IS NOT NULL");
    while (s.step())
      rows[s.text(0)] = {s.text(1), s.text(2)};
    Statement m(db_->db, "SELECT key, value FROM metrics WHERE run_id = ?");
    for (const RunSpec& r : runs_) {
      auto row = rows.find(r.id);
      if (row == rows.end()) continue;
      SweepReportRun rr;
      rr.index = r.index;
      rr.id = r.id;
      rr.seed = r.seed;
      rr.label = r.label;
      rr.points = r.points;
      rr.ok = row->second.first == "ok";
      rr.error = row->second.second;
      m.bind(1, r.id);
      while (m.step())
        rr.metrics[m.text(0)] = m.number(1);
      m.reset();
      add_derived_metrics(rr.metrics);
      report.runs.push_back(std::move(rr));
    }
  }
  report.total_runs = runs_.size();
  const fs::path tmp = out / "report.html.partial";
  try {
    write_file(tmp, render_sweep_report(report));
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, out / "report.html");
  return counts_;
}

SweepCounts run_sweep_locally(const SweepDef& sweep, const SweepOptions& options,
                              const std::function<void(const RunResult&)>& on_result) {
  SweepSession results(sweep, expand_sweep(sweep), options);
  {
    SweepWorkers workers(sweep, results.runs(), options.out_dir, options.jobs);
    for (std::size_t index : results.pending())
      workers.submit(index);
    while (workers.in_flight() > 0)
      if (auto r = workers.next(std::chrono::milliseconds(500))) {
        results.record(*r);
        if (on_result) on_result(*r);
      }
  }
  return results.finish();
}

}  // namespace masnet::scenarios
