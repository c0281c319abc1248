// Sweep files: expansion (lists, ranges, zip, variants, seeds), stable run ids, positioned
// errors, and the metrics recorded per run.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "scenarios/sweep/sweep.hpp"
#include "sweep_helpers.hpp"

using namespace masnet::scenarios;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kSource = MASNET_SOURCE_DIR;
const std::string kBase = kSource + "/scenarios/paper/acoustic_tracking.yaml";
// A sweep file "in" scenarios/sweeps/, so that `base: ../paper/...` resolves as in the examples.
const std::string kInline = kSource + "/scenarios/sweeps/inline.yaml";

SweepDef parse(const std::string& text) {
  SweepLoad loaded = load_sweep_text(text, kInline);
  std::string messages;
  for (const auto& d : loaded.diagnostics)
    messages += d.text() + "\n";
  INFO(messages);
  REQUIRE(loaded.sweep);
  return *loaded.sweep;
}

std::vector<std::string> errors(const std::string& text) {
  return masnet::test::sweep_errors(text, kInline);
}

std::vector<json> values_of(const SweepDef& def, std::size_t axis) {
  std::vector<json> v;
  for (const auto& p : def.axes.at(axis).points)
    v.push_back(p.overrides.at(0).value);
  return v;
}

}  // namespace

TEST_CASE("A sweep expands lists as a cartesian product with the seeds varying fastest",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "seeds: 3\n"
      "vary:\n"
      "  protocol.kind: [oracle, gabriel]\n"
      "  radio.loss: [0, 0.25]\n");
  CHECK(def.base_path == fs::path(kBase).lexically_normal().string());
  CHECK(def.seeds == std::vector<std::uint64_t>{1, 2, 3});
  CHECK(def.parameters == std::vector<std::string>{"protocol.kind", "radio.loss"});
  const std::vector<RunSpec> runs = expand_sweep(def);
  REQUIRE(runs.size() == 12);
  CHECK(runs[0].overrides == std::vector<std::string>{"protocol.kind=\"oracle\"", "radio.loss=0"});
  CHECK(runs[0].seed == 1);
  CHECK(runs[2].seed == 3);
  CHECK(runs[3].overrides ==
        std::vector<std::string>{"protocol.kind=\"oracle\"", "radio.loss=0.25"});
  CHECK(runs[6].parameters == json{{"protocol.kind", "gabriel"}, {"radio.loss", 0}});
  CHECK(runs[11].label == "protocol.kind=gabriel radio.loss=0.25 seed=3");
  for (std::size_t i = 0; i < runs.size(); ++i)
    CHECK(runs[i].index == i);
}

TEST_CASE("Ranges are inclusive and give round decimal values, integers stay integers",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "vary:\n"
      "  radio.loss: {from: 0.0, to: 0.5, step: 0.1}\n"
      "  protocol.decay.patience: {from: 1, to: 7, step: 3}\n"
      "  protocol.decay.step: {from: 0.3, to: 0.1, step: -0.1}\n"
      "  radio.latency: {from: 1e-4, to: 3e-4, step: 1e-4}\n");
  CHECK(values_of(def, 0) == std::vector<json>{0.0, 0.1, 0.2, 0.3, 0.4, 0.5});
  CHECK(values_of(def, 0)[3].dump() == "0.3");  // not 0.30000000000000004
  CHECK(values_of(def, 1) == std::vector<json>{1, 4, 7});
  CHECK(values_of(def, 1)[0].is_number_integer());
  CHECK(values_of(def, 2) == std::vector<json>{0.3, 0.2, 0.1});
  CHECK(values_of(def, 3) == std::vector<json>{0.0001, 0.0002, 0.0003});
  CHECK(expand_sweep(def).size() == 6 * 3 * 3 * 3);
  // Directly: many small steps still reach `to` exactly once.
  const auto fine = sweep_range(0.0, 1.0, 0.01, 2, false);
  REQUIRE(fine.size() == 101);
  CHECK(fine.back() == json(1.0));
  CHECK(fine[7] == json(0.07));
  CHECK(sweep_range(0, 1, 0, 0, true).empty());
  CHECK(sweep_range(1, 0, 0.5, 1, false).empty());
}

TEST_CASE("Zipped keys vary together - variants are named override sets - seeds may be listed",
          "[scenarios]") {
  const SweepDef def = parse(
      "base: ../paper/acoustic_tracking.yaml\n"
      "seeds: [7, 3]\n"
      "set: {duration: 2.0}\n"
      "variants:\n"
      "  - {name: seed_rule, protocol.kind: radius_doubling, protocol.criterion: sensors}\n"
      "  - {name: cortes, protocol.kind: radius_doubling, protocol.criterion: vertices, "
      "protocol.growth: double}\n"
      "vary:\n"
      "  protocol.decay.patience: [1, 3, 5]\n"
      "  radio.loss: [0, 0.1]\n"
      "  protocol.decay.step: [0.01, 0.02, 0.04]\n"
      "zip: [[protocol.decay.patience, protocol.decay.step]]\n");
  REQUIRE(def.axes.size() == 3);  // variants, the zip group, radio.loss
  CHECK(def.axes[0].name == "variant");
  CHECK(def.axes[1].keys ==
        std::vector<std::string>{"protocol.decay.patience", "protocol.decay.step"});
  CHECK(def.axes[1].points[2].label == "(5, 0.04)");
  CHECK(def.parameters == std::vector<std::string>{"variant", "protocol.kind", "protocol.criterion",
                                                   "protocol.growth", "protocol.decay.patience",
                                                   "protocol.decay.step", "radio.loss"});
  const std::vector<RunSpec> runs = expand_sweep(def);
  REQUIRE(runs.size() == 2 * 3 * 2 * 2);
  CHECK(runs[0].seed == 7);
  CHECK(runs[1].seed == 3);
  // set first, then the variant, then the varied keys.
  CHECK(runs[0].overrides ==
        std::vector<std::string>{"duration=2.0", "protocol.kind=\"radius_doubling\"",
                                 "protocol.criterion=\"sensors\"", "protocol.decay.patience=1",
                                 "protocol.decay.step=0.01", "radio.loss=0"});
  const RunSpec& last = runs.back();
  CHECK(last.parameters["variant"] == "cortes");
  CHECK(last.parameters["protocol.growth"] == "double");
  CHECK(last.parameters["protocol.decay.patience"] == 5);
  CHECK(last.parameters["protocol.decay.step"] == 0.04);
  CHECK_FALSE(runs[0].parameters.contains("protocol.growth"));
}

TEST_CASE("Run ids are stable: the same base, overrides and seed give the same id", "[scenarios]") {
  const std::string text =
      "base: ../paper/acoustic_tracking.yaml\nseeds: 2\nvary: {radio.loss: [0, 0.1]}\n";
  const std::vector<RunSpec> a = expand_sweep(parse(text)), b = expand_sweep(parse(text));
  REQUIRE(a.size() == 4);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].id == b[i].id);
    CHECK(a[i].id.size() == 16);
    ids.insert(a[i].id);
  }
  CHECK(ids.size() == 4);
  // The same run in another sweep (another order, a comment, other values beside it) keeps its id.
  const std::vector<RunSpec> c = expand_sweep(
      parse("# the same runs, and more\nbase: ../paper/acoustic_tracking.yaml\nseeds: [2, 1, 5]\n"
            "vary: {radio.loss: [0.1, 0.3, 0]}\n"));
  std::set<std::string> c_ids;
  for (const auto& r : c)
    c_ids.insert(r.id);
  for (const auto& id : ids)
    CHECK(c_ids.count(id));
  // Direct: order of overrides of distinct keys does not matter, values and seed do.
  const std::string k = "0123456789abcdef";
  const SweepOverride loss{"radio.loss", 0.1}, kind{"protocol.kind", "oracle"};
  CHECK(sweep_run_id(k, {loss, kind}, 1) == sweep_run_id(k, {kind, loss}, 1));
  CHECK(sweep_run_id(k, {loss, kind}, 1) != sweep_run_id(k, {loss, kind}, 2));
  CHECK(sweep_run_id(k, {loss}, 1) != sweep_run_id(k, {SweepOverride{"radio.loss", 0.2}}, 1));
  CHECK(sweep_run_id(k, {loss}, 1) != sweep_run_id("fedcba9876543210", {loss}, 1));
}

TEST_CASE("A bad sweep file gets file:line:col errors", "[scenarios]") {
  const std::string f = kInline;
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\n"
               "vary:\n"
               "  protocol.decay.patience: [1, 3, 5]\n"
               "  protocol.decay.step: [0.01, 0.02]\n"
               "zip: [[protocol.decay.patience, protocol.decay.step]]\n") ==
        std::vector<std::string>{
            f + ":5:7: zip[0]: keys zipped together need lists of the same length, but "
                "'protocol.decay.patience' has 3 values and 'protocol.decay.step' has 2"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nseed: 3\n") ==
        std::vector<std::string>{
            f + ":2:1: unknown key 'seed' in a sweep file (allowed: base, seeds, set, "
                "variants, vary, zip, output, report, name, description) (did you mean 'seeds'?)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nseeds: 0\n") ==
        std::vector<std::string>{
            f + ":2:8: seeds: expected a count between 1 and 1000000 (seeds 1..N) or a "
                "list of seeds, got '0'"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  radio.loss: {from: 0, to: 1, step: "
               "-0.1}\n") ==
        std::vector<std::string>{
            f + ":3:38: vary.radio.loss.step: must be non-zero and go from 'from' towards "
                "'to' (from 0 to 1 by -0.1)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  radio.loss: 0.1\n") ==
        std::vector<std::string>{
            f + ":3:15: vary.radio.loss: expected a list of values, e.g. [0, 0.1, 0.2], "
                "or a range {from: 0, to: 0.5, step: 0.1}"});
  CHECK(errors("base: ../paper/missing.yaml\n") ==
        std::vector<std::string>{f + ":1:7: base: cannot read the scenario '" +
                                 (fs::path(kSource) / "scenarios/paper/missing.yaml").string() +
                                 "' (No such file or directory)"});
  // A key the scenario does not have is the sweep file's error, located in the sweep file.
  CHECK(
      errors("base: ../paper/acoustic_tracking.yaml\nvary:\n  protocol.knd: [oracle, gabriel]\n") ==
      std::vector<std::string>{
          f + ":3:3: 'protocol.knd' is not a key of the base scenario: unknown key "
              "'knd' in 'protocol' (did you mean 'kind'?)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nset: {duration: 1}\nvary: {duration: [1, "
               "2]}\n") ==
        std::vector<std::string>{
            f + ":3:8: vary: 'duration' is also fixed under 'set'; give it in one place"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary: {seed: [1, 2]}\n") ==
        std::vector<std::string>{
            f + ":2:8: 'seed' cannot be overridden: every run gets its seed from 'seeds' "
                "(a count or a list)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\nvary: {radio.loss: [0.1, 0.2, 0.1]}\n") ==
        std::vector<std::string>{f + ":2:31: vary.radio.loss: the value 0.1 is listed twice"});
  CHECK(
      errors(
          "base: ../paper/acoustic_tracking.yaml\nvariants:\n  - {name: a, protocol.kind: oracle}\n"
          "  - {name: b, protocol.kind: oracle}\n") ==
      std::vector<std::string>{
          f + ":4:5: variants[1]: sets the same keys to the same values as variants[0] "
              "(the runs would be identical)"});
  CHECK(errors("base: ../paper/acoustic_tracking.yaml\noutput: {dir: x, keep: true}\n") ==
        std::vector<std::string>{f + ":2:18: unknown key 'keep' in 'output'"});
  CHECK(errors("base: [oops\n").at(0).rfind(f + ":", 0) == 0);
}

TEST_CASE("Summary metrics flatten to dotted keys and SQL column names", "[scenarios]") {
  const json summary = {
      {"seed", 3},
      {"wall_time_s", 0.5},
      {"fingerprint", "abc"},
      {"messages", {{"total", {{"count", 10}}}, {"by_type", {{"DISCOVER", {{"count", 4}}}}}}},
      {"tracking", {{"robots_per_target", {5, 4}}}},
      {"scenario", {{"robots", 9}, {"resolved", {{"duration", 5.0}}}}},
      {"flag", true}};
  const auto flat = flatten_metrics(summary);
  const std::map<std::string, double> m(flat.begin(), flat.end());
  CHECK(m == std::map<std::string, double>{{"flag", 1.0},
                                           {"messages.by_type.DISCOVER.count", 4.0},
                                           {"messages.total.count", 10.0},
                                           {"scenario.robots", 9.0},
                                           {"tracking.robots_per_target.0", 5.0},
                                           {"tracking.robots_per_target.1", 4.0},
                                           {"wall_time_s", 0.5}});
  CHECK(sanitize_column("messages.by_type.DISCOVER.count") == "messages_by_type_discover_count");
  CHECK(sanitize_column("p_protocol.kind") == "p_protocol_kind");
}
