// Sweep files against hostile input and the limits of docs/sweeps.md: sweeps too large to
// expand, alias bombs, extra documents, paths that are not regular files.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "loader_helpers.hpp"
#include "scenarios/sweep/sweep.hpp"

using namespace masnet::scenarios;

namespace {

const std::string kScenarios = MASNET_SOURCE_DIR "/scenarios";

using masnet::test::texts;

}  // namespace

TEST_CASE("a sweep with too many runs is refused before it is expanded", "[scenarios]") {
  const std::string file = kScenarios + "/sweeps/inline.yaml";
  const SweepLoad many = load_sweep_text(
      "base: ../paper/acoustic_tracking.yaml\nseeds: 1000\nvary:\n  radio.loss: {from: 0, to: "
      "0.99, step: 0.01}\n"
      "  radio.max_range: [1, 2]\n",
      file);
  CHECK(texts(many.diagnostics) ==
        std::vector<std::string>{
            file + ":4:3: the sweep would have 200000 runs (100 radio.loss × 2 radio.max_range × "
                   "1000 seeds), more than the limit of 100000 (docs/sweeps.md, \"Limits\")"});
  // 10^5 values on each of four keys: the product overflows 64 bits long before it is built.
  std::string text = "base: ../paper/acoustic_tracking.yaml\nvary:\n";
  for (const char* key : {"radio.loss", "radio.jitter", "radio.latency", "protocol.decay.step"})
    text += std::string("  ") + key + ": {from: 0, to: 0.99999, step: 0.00001}\n";
  const SweepLoad overflow = load_sweep_text(text, file);
  REQUIRE(overflow.diagnostics.size() == 1);
  CHECK(overflow.diagnostics[0].message.rfind("the sweep would have more than 1.8e+19 runs", 0) ==
        0);
}

TEST_CASE("a sweep file's aliases, tags and extra documents are refused", "[scenarios]") {
  const std::string file = kScenarios + "/sweeps/inline.yaml";
  std::string bomb =
      "base: ../paper/acoustic_tracking.yaml\nx0: &x0 [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n";
  for (int i = 1; i < 8; ++i) {
    bomb += "x" + std::to_string(i) + ": &x" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k)
      bomb += (k ? ", *x" : "*x") + std::to_string(i - 1);
    bomb += "]\n";
  }
  bomb += "vary:\n  radio.loss: *x7\n";
  CHECK(texts(load_sweep_text(bomb, file).diagnostics) ==
        std::vector<std::string>{file +
                                 ":6:45: the aliases (*name) repeat more than 100000 nodes in all "
                                 "(docs/scenario-reference.md, \"Limits\")"});
  CHECK(texts(load_sweep_text("base: ../paper/acoustic_tracking.yaml\n---\n", file).diagnostics) ==
        std::vector<std::string>{
            file + ":2:1: a second YAML document starts here (the file must hold a single "
                   "document; remove the '---' and what follows)"});
  const SweepLoad fifo = load_sweep("/dev/zero");
  CHECK(texts(fifo.diagnostics) ==
        std::vector<std::string>{"/dev/zero:1:1: cannot read the sweep file (not a regular file)"});
}
