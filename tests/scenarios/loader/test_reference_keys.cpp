// The scenario reference tells the truth (docs/scenario-reference.md): every key the loader
// knows is documented there, and every key documented there is one the loader knows. Each key
// table of the page is preceded by `<!-- keys: PREFIX ... -->`, the dotted path(s) its first
// column is relative to; the loader notes every key it reads or rejects for a scenario's kinds
// (LoadResult::known_keys). A corpus of scenarios covering every kind and layout is loaded.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "scenarios/loader/scenario.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;

namespace {

const std::string kSource = MASNET_SOURCE_DIR;

// Every key documented by a marked table, with the parents of dotted keys ("decay.min" also
// documents "decay").
std::set<std::string> documented_keys() {
  std::ifstream in(kSource + "/docs/scenario-reference.md");
  REQUIRE(in);
  std::set<std::string> keys;
  std::vector<std::string> prefixes;
  bool in_table = false;
  const std::regex marker(R"(<!-- keys:(.*)-->)"), token("`([A-Za-z_][A-Za-z0-9_.]*)`");
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, marker)) {
      prefixes.clear();
      std::istringstream words(m[1].str());
      for (std::string w; words >> w;)
        prefixes.push_back(w == "." ? "" : w);
      in_table = false;
      continue;
    }
    if (prefixes.empty()) continue;
    if (line.rfind("|", 0) != 0) {
      if (in_table) prefixes.clear();  // the marked table ended
      continue;
    }
    in_table = true;
    const std::size_t end = line.find('|', 1);
    const std::string first = line.substr(1, end - 1);
    if (first.find("---") != std::string::npos || first.find("key") != std::string::npos) continue;
    for (auto it = std::sregex_iterator(first.begin(), first.end(), token);
         it != std::sregex_iterator(); ++it)
      for (const std::string& prefix : prefixes) {
        std::string key = prefix.empty() ? (*it)[1].str() : prefix + "." + (*it)[1].str();
        for (std::size_t dot = key.find('.'); dot != std::string::npos;
             dot = key.find('.', dot + 1)) {
          std::string parent = key.substr(0, dot);
          if (parent.size() > 2 && parent.compare(parent.size() - 2, 2, "[]") == 0)
            parent.resize(parent.size() - 2);
          keys.insert(parent);
        }
        keys.insert(key);
      }
  }
  return keys;
}

// The loader's known keys over the corpus: every scenario shipped, and texts for the kinds and
// layouts no shipped scenario uses.
std::set<std::string> loader_keys() {
  std::set<std::string> keys;
  auto add = [&](const LoadResult& r, const std::string& what) {
    std::string problems;
    for (const auto& d : r.diagnostics)
      problems += d.text() + "\n";
    INFO(what << "\n" << problems);
    CHECK(r.scenario);
    keys.insert(r.known_keys.begin(), r.known_keys.end());
  };
  LoadOptions count_only;
  count_only.build_sensors = false;
  for (const auto& dir : {"paper", "examples", "examples/protocol_comparison", "bench"})
    for (const auto& entry : fs::directory_iterator(kSource + "/scenarios/" + dir))
      if (entry.path().extension() == ".yaml")
        add(load_scenario(entry.path().string(), {}, std::nullopt, count_only),
            entry.path().string());
  const std::string file = kSource + "/tests/scenarios/reference/corpus.yaml";
  const std::string base = masnet::test::slurp(file);
  const std::vector<std::vector<std::string>> variants = {
      {"field={kind: gaussian, bumps: [{waypoints: [[0.2, 0.2], [0.8, 0.8]], speed: 0.1, loop: "
       "true, sigma: 0.1}]}",
       "sensors={layout: random, count: 50}",
       "robots={layout: random, count: 3, dynamics: discrete_lloyd}",
       "density_scaling={kind: power, gamma: 2}", "protocol={kind: fixed_radius, radius: 0.2}",
       "beacons={senders: all, period: 0.5, range: 0.1}", "limits={allow_huge: false}"},
      {"radio={level: csma, propagation: {model: log_distance}, capture_threshold: 3, energy: "
       "{model: states, tx_currents: [[0, 0.0174]]}}"},
      {"field={kind: uniform, value: 2}", "robots={layout: positions, positions: [[0.5, 0.5]]}",
       "density_scaling={kind: saturate, c: 2}", "sensors={layout: grid, alignment: interior}"},
      {"faults=[{at: 0.1, until: 0.5, kill: robots, ids: [0]}, {at: 0.1, kill: sensors, "
       "fraction: 0.5}, {at: 0.1, kill: robots, region: {center: [0.5, 0.5], radius: 0.2}}, "
       "{at: 0.2, partition: {line: [[0.5, 0], [0.5, 1]]}}, {at: 0.2, degrade: {loss: 0.5, "
       "region: {polygon: [[0, 0], [1, 0], [0, 1]]}}}]"},
  };
  for (const auto& sets : variants)
    add(load_scenario_text(base, file, sets, std::nullopt, count_only), sets[0]);
  return keys;
}

}  // namespace

TEST_CASE("Every key the loader knows is in the scenario reference, and every key there is known",
          "[scenarios]") {
  const std::set<std::string> documented = documented_keys(), known = loader_keys();
  REQUIRE(documented.size() > 50);
  std::string undocumented, unknown;
  for (const auto& k : known)
    if (!documented.count(k)) undocumented += "  " + k + "\n";
  for (const auto& k : documented)
    if (!known.count(k)) unknown += "  " + k + "\n";
  INFO("read by the loader, missing from docs/scenario-reference.md:\n"
       << undocumented << "documented, but the loader never reads them:\n"
       << unknown);
  CHECK(undocumented.empty());
  CHECK(unknown.empty());
}

TEST_CASE("A protocol knob of another kind is a located warning, not an error", "[scenarios]") {
  const std::string text =
      "duration: 1\nprotocol:\n  kind: oracle\n  growth: double\n  decay: {patience: 2}\n  radius: "
      "0.2\n";
  const LoadResult r = load_scenario_text(text, "s.yaml", {});
  REQUIRE(r.scenario);
  std::vector<std::string> warnings;
  for (const auto& w : r.warnings)
    warnings.push_back(w.text());
  CHECK(warnings == std::vector<std::string>{"s.yaml:4:11: protocol.growth: applies to protocol "
                                             "kind radius_doubling, not oracle: it is ignored",
                                             "s.yaml:5:10: protocol.decay: applies to protocol "
                                             "kind radius_doubling, not oracle: it is ignored",
                                             "s.yaml:6:11: protocol.radius: applies to protocol "
                                             "kind fixed_radius, not oracle: it is ignored"});
  // The same knobs with the kind they belong to: no warning.
  CHECK(load_scenario_text("duration: 1\nprotocol: {kind: radius_doubling, growth: double}\n",
                           "s.yaml", {})
            .warnings.empty());
  const LoadResult set =
      load_scenario_text("duration: 1\n", "s.yaml", {"protocol.kind=none", "protocol.period=0.1"});
  REQUIRE(set.warnings.size() == 1);
  CHECK(set.warnings[0].text() ==
        "--set protocol.period=0.1: protocol.period: applies to protocol kind radius_doubling, "
        "oracle, fixed_radius "
        "and gabriel, not none: it is ignored");
}
