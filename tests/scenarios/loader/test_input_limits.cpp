// The loader against hostile input that no fixture file can hold (FIFOs, symlink loops, command
// line values) and the limits of docs/scenario-reference.md: how values are shown, null for
// every kind of key, paths that are not regular files, --seed's range, safe names, counting
// without building (sweep files: tests/scenarios/sweep/test_sweep_limits.cpp).
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "loader_helpers.hpp"
#include "scenarios/loader/input.hpp"
#include "scenarios/loader/scenario.hpp"

namespace fs = std::filesystem;
using namespace masnet::scenarios;

namespace {

const std::string kMasnet = MASNET_BINARY_DIR "/scenarios/masnet";
const std::string kScenarios = MASNET_SOURCE_DIR "/scenarios";

using masnet::test::texts;
using TempDir = masnet::test::TempDir;

std::vector<std::string> problems(const std::string& text,
                                  const std::vector<std::string>& sets = {}) {
  return texts(load_scenario_text(text, "inline.yaml", sets).diagnostics);
}

using masnet::test::Outcome;

// masnet's standard error (its messages), with a time limit.
Outcome run_masnet(const std::string& args) {
  return masnet::test::shell("timeout 20 " + kMasnet + " " + args + " 2>&1 >/dev/null");
}

}  // namespace

TEST_CASE("values in messages are escaped and cut at 80 characters", "[scenarios]") {
  CHECK(shown_text("radius_doublng") == "radius_doublng");
  // UTF-8 stays as written; control bytes and bytes that are not UTF-8 are escaped.
  CHECK(shown_text("κ ±") == "κ ±");
  CHECK(shown_text("a\tb\x1b[31m") == "a\\x09b\\x1B[31m");
  CHECK(shown_text("caf\xb1") == "caf\\xB1");
  CHECK(shown_text(std::string(80, 'x')) == std::string(80, 'x'));
  CHECK(shown_text(std::string(1000000, 'x')) == std::string(80, 'x') + "… (1000000 bytes in all)");
  CHECK(first_invalid_utf8("ok é") == std::string::npos);
  CHECK(first_invalid_utf8("ab\xc3") == 2);         // cut sequence
  CHECK(first_invalid_utf8("\xc0\xaf") == 0);       // overlong
  CHECK(first_invalid_utf8("x\xed\xa0\x80") == 1);  // surrogate
}

TEST_CASE("a --set value is cut in its location too", "[scenarios]") {
  const std::string huge(1 << 20, 'a');
  CHECK(problems("duration: 1\n", {"radio.level=" + huge}) ==
        std::vector<std::string>{
            "--set radio.level=" + std::string(68, 'a') +
            "… (1048588 bytes in all): "
            "radio.level: expected one of ideal, airtime, collision, csma, got '" +
            std::string(80, 'a') + "… (1048576 bytes in all)'"});
}

TEST_CASE("a key given without a value is an error for every kind of key", "[scenarios]") {
  CHECK(problems("duration: 1\nseed:\n") ==
        std::vector<std::string>{
            "inline.yaml:2:1: seed: expected a whole number, got nothing (null)"});
  CHECK(problems("duration: 1\noutput: {figures: ~}\n") ==
        std::vector<std::string>{
            "inline.yaml:2:10: output.figures: expected true or false, got nothing (null)"});
  CHECK(problems("duration: 1\nname: null\n") ==
        std::vector<std::string>{"inline.yaml:2:1: name: expected a text, got nothing (null)"});
  CHECK(problems("duration: 1\nfield:\n  kind: acoustic\n  targets:\n") ==
        std::vector<std::string>{
            "inline.yaml:4:3: field.targets: expected a list, got nothing (null)",
            "inline.yaml:4:3: field.targets: an acoustic field needs at least one target"});
  CHECK(problems("duration: 1\nfield:\n  kind: gaussian\n  bumps: [{start: ~}]\n") ==
        std::vector<std::string>{
            "inline.yaml:4:12: field.bumps[0].start: expected a point [x, y], got nothing (null)"});
  CHECK(problems("duration: 1\ndomain: {rectangle: }\n") ==
        std::vector<std::string>{
            "inline.yaml:2:10: domain.rectangle: expected a list of numbers, got nothing (null)",
            "inline.yaml:2:10: domain.rectangle: expected [xmin, ymin, xmax, ymax] with xmin < "
            "xmax and ymin < ymax"});
  // On the command line: `--set protocol.kind=` is not radius_doubling.
  CHECK(problems("duration: 1\nprotocol: {kind: none}\n", {"protocol.kind="}) ==
        std::vector<std::string>{
            "--set protocol.kind=: protocol.kind: expected one of none, radius_doubling, "
            "oracle, fixed_radius, gabriel, got nothing (null)"});
}

TEST_CASE("values given with --set must be UTF-8 and free of YAML tags", "[scenarios]") {
  CHECK(problems("duration: 1\n", {"name=caf\xb1"}) ==
        std::vector<std::string>{"--set name=caf\\xB1: the text is not valid UTF-8 (byte 0xB1 "
                                 "here); save the file as UTF-8"});
  CHECK(problems("duration: 1\n", {"duration=!!str 5"}) ==
        std::vector<std::string>{
            "--set duration=!!str 5: YAML tags are not supported (got '!!str'); write the "
            "value alone, quoted if it must stay a text"});
}

TEST_CASE("a scenario path that is not a readable regular file is located at 1:1", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string missing = (dir.path / "missing.yaml").string();
  const std::string fifo = (dir.path / "fifo.yaml").string();
  const std::string loop = (dir.path / "loop.yaml").string();
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  fs::create_symlink(loop, loop);
  CHECK(texts(load_scenario(missing, {}).diagnostics) ==
        std::vector<std::string>{
            missing + ":1:1: cannot read the scenario file (No such file or directory)"});
  CHECK(texts(load_scenario(dir.path.string(), {}).diagnostics) ==
        std::vector<std::string>{dir.path.string() +
                                 ":1:1: cannot read the scenario file (Is a directory)"});
  // A FIFO would block the open: refused from its stat alone.
  CHECK(
      texts(load_scenario(fifo, {}).diagnostics) ==
      std::vector<std::string>{fifo + ":1:1: cannot read the scenario file (not a regular file)"});
  CHECK(texts(load_scenario(loop, {}).diagnostics) ==
        std::vector<std::string>{
            loop + ":1:1: cannot read the scenario file (Too many levels of symbolic links)"});
  CHECK(texts(load_scenario("/dev/zero", {}).diagnostics) ==
        std::vector<std::string>{
            "/dev/zero:1:1: cannot read the scenario file (not a regular file)"});
  // validate and run agree, with exit 2.
  for (const std::string& command :
       {std::string("validate "), "run --quiet --out " + (dir.path / "out").string() + " "}) {
    const Outcome outcome = run_masnet(command + fifo);
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.output == fifo + ":1:1: cannot read the scenario file (not a regular file)\n");
  }
  CHECK_FALSE(fs::exists(dir.path / "out"));
}

TEST_CASE("a scenario file larger than 16 MiB is refused without reading it", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string big = (dir.path / "big.yaml").string();
  { std::ofstream create(big); }
  fs::resize_file(big, kMaxScenarioFileBytes + 1);
  CHECK(texts(load_scenario(big, {}).diagnostics) ==
        std::vector<std::string>{
            big + ":1:1: cannot read the scenario file (larger than the limit of 16777216 bytes)"});
}

TEST_CASE("a sensor file that is not a regular file is reported at the file key", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string fifo = (dir.path / "sensors.csv").string();
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const std::string text = "duration: 1\nsensors:\n  layout: file\n  file: sensors.csv\n";
  CHECK(texts(load_scenario_text(text, (dir.path / "s.yaml").string(), {}).diagnostics) ==
        std::vector<std::string>{(dir.path / "s.yaml").string() +
                                 ":4:9: sensors.file: cannot read sensor file '" + fifo +
                                 "' (not a regular file)"});
  CHECK(texts(load_scenario_text("duration: 1\nsensors: {layout: file, file: /dev/zero}\n",
                                 "s.yaml", {})
                  .diagnostics) ==
        std::vector<std::string>{
            "s.yaml:2:31: sensors.file: cannot read sensor file '/dev/zero' (not a regular file)"});
}

TEST_CASE("sensors outside the domain are listed up to ten, then counted", "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  {
    std::ofstream csv(dir.path / "sensors.csv");
    csv << "0.5,0.5\n";
    for (int i = 0; i < 15; ++i)
      csv << "2," << i << "\n";
  }
  const std::vector<std::string> lines =
      texts(load_scenario_text("duration: 1\nsensors: {layout: file, file: sensors.csv}\n",
                               (dir.path / "s.yaml").string(), {})
                .diagnostics);
  const std::string csv = (dir.path / "sensors.csv").string();
  REQUIRE(lines.size() == 11);
  CHECK(lines[0] == csv + ":2:1: sensor 1 at (2, 0) lies outside the domain");
  CHECK(lines[9] == csv + ":11:1: sensor 10 at (2, 9) lies outside the domain");
  CHECK(lines[10] == csv + ":12:1: ... and 5 more sensors outside the domain");
}

TEST_CASE("the --seed option takes 0 to 2^63-1 like the seed key, and nothing is clamped",
          "[scenarios]") {
  TempDir dir;
  REQUIRE(!dir.path.empty());
  const std::string scenario = kScenarios + "/examples/beacons.yaml";
  for (const std::string seed :
       {"99999999999999999999", "9223372036854775808", "-1", "1e3", "7x"}) {
    INFO(seed);
    const Outcome outcome = run_masnet("run " + scenario + " --quiet --out " +
                                       (dir.path / "out").string() + " --seed " + seed);
    CHECK(outcome.exit_code == 2);
    CHECK(outcome.output ==
          "--seed " + seed + ": expected a whole number between 0 and 9223372036854775807\n");
    CHECK_FALSE(fs::exists(dir.path / "out"));
  }
  const LoadResult largest =
      load_scenario_text("duration: 1\nseed: 9223372036854775807\n", "s.yaml", {});
  REQUIRE(largest.scenario);
  CHECK(largest.scenario->seed == 9223372036854775807ull);
  CHECK(problems("duration: 1\nseed: 9223372036854775808\n") ==
        std::vector<std::string>{
            "inline.yaml:2:7: seed: expected a whole number, got '9223372036854775808'"});
}

TEST_CASE("a default name from an unsafe file name is made safe", "[scenarios]") {
  CHECK(valid_name("scaling_1e6"));
  CHECK_FALSE(valid_name(".hidden"));
  CHECK_FALSE(valid_name("-rf"));
  CHECK_FALSE(valid_name(std::string(65, 'a')));
  CHECK(sanitized_name("my run!") == "my_run_");
  CHECK(sanitized_name("..hidden") == "hidden");
  CHECK(sanitized_name("---") == "scenario");
  CHECK(sanitized_name(std::string(100, 'b')) == std::string(64, 'b'));
  const LoadResult loaded = load_scenario_text("duration: 1\n", "/tmp/my run (2).yaml", {});
  REQUIRE(loaded.scenario);
  CHECK(loaded.scenario->name == "my_run__2_");
  CHECK(loaded.scenario->resolved["name"] == "my_run__2_");
  CHECK(texts(load_scenario_text("duration: 1\n", "caf\xb1.yaml", {}).diagnostics) ==
        std::vector<std::string>{"caf\\xB1.yaml:1:1: the file name is not valid UTF-8"});
}

TEST_CASE("counting the sensors without building them gives the same scenario", "[scenarios]") {
  LoadOptions count_only;
  count_only.build_sensors = false;
  for (const char* file :
       {"examples/beacons.yaml", "examples/static_coverage.yaml", "paper/acoustic_tracking.yaml",
        "paper/pollution_control.yaml", "bench/scaling_1e5.yaml"}) {
    INFO(file);
    const LoadResult built = load_scenario(kScenarios + "/" + file, {});
    const LoadResult counted = load_scenario(kScenarios + "/" + file, {}, std::nullopt, count_only);
    REQUIRE(built.scenario);
    REQUIRE(counted.scenario);
    CHECK(built.scenario->sensor_count == built.scenario->world.sensors.size());
    CHECK(counted.scenario->sensor_count == built.scenario->sensor_count);
    CHECK(counted.scenario->world.sensors.empty());
    CHECK(counted.scenario->resolved == built.scenario->resolved);
    // No limits key in the file: none in the resolved scenario either.
    CHECK_FALSE(built.scenario->resolved.contains("limits"));
  }
}

TEST_CASE("limits.allow_huge raises the node limits unless the caller forbids it", "[scenarios]") {
  const std::string text =
      "duration: 1\nsensors: {layout: random, count: 20000000}\nlimits: {allow_huge: true}\n";
  LoadOptions options;
  options.build_sensors = false;
  const LoadResult allowed = load_scenario_text(text, "s.yaml", {}, std::nullopt, options);
  REQUIRE(allowed.scenario);
  CHECK(allowed.scenario->sensor_count == 20000000);
  CHECK(allowed.scenario->resolved["limits"]["allow_huge"] == true);
  options.allow_huge = false;  // as a fuzzer does
  CHECK(texts(load_scenario_text(text, "s.yaml", {}, std::nullopt, options).diagnostics) ==
        std::vector<std::string>{
            "s.yaml:2:34: sensors.count: more than 10000000 sensors (got 20000000) "
            "(limits.allow_huge: true allows up to 100000000)"});
  // The work budget too: 10^10 protocol updates pass only with the opt-in.
  CHECK(problems("duration: 1000\nprotocol: {period: 1e-6}\nlimits: {allow_huge: true}\n").empty());
}
