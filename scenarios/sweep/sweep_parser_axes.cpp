// A sweep file's `vary` and `zip`: lists, ranges and zipped groups of values read into axes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "scenarios/sweep/sweep_parser.hpp"

namespace masnet::scenarios::sweep_parsing {
namespace fs = std::filesystem;

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

}  // namespace masnet::scenarios::sweep_parsing
