// Warnings about degenerate runs (docs/outputs.md, summary.json `warnings`): each threshold
// against crafted metrics, and a real lossy run against a healthy one.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "scenarios/run/run_warnings.hpp"
#include "text_files.hpp"

using namespace masnet::scenarios;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {
json metrics(double updates, double correctness, double truncated, double no_mass, double dead) {
  return json{{"protocol",
               {{"name", "radius_doubling"},
                {"updates", updates},
                {"cell_correctness", correctness},
                {"truncated", truncated},
                {"no_mass_updates", no_mass}}},
              {"energy_j", {{"nodes_dead", dead}}}};
}
}  // namespace

TEST_CASE("A healthy run has no warnings, each degenerate symptom its own", "[scenarios]") {
  CHECK(run_warnings(metrics(956, 0.93, 95, 0, 0), 0.0).empty());  // 9.9 % truncated: fine
  CHECK(run_warnings(metrics(956, 0.039, 909, 0, 0), 0.5) ==
        std::vector<std::string>{
            "only 3.9 % of the updates built the robot's true Voronoi cell (cell correctness "
            "0.039) (radio.loss "
            "is 0.5): the protocol's cells, costs and figures describe a degraded run",
            "909 of 956 updates stopped at their radius cap (radio.max_range; protocol.radius for "
            "fixed_radius) "
            "before their cell was certain (radio.loss is 0.5)"});
  CHECK(run_warnings(metrics(100, 0.5, 0, 26, 0), 0.0) ==
        std::vector<std::string>{
            "26 of 100 updates heard no sensor reading with mass: those robots did not move"});
  CHECK(run_warnings(metrics(100, 0.99, 0, 0, 1), 0.0) ==
        std::vector<std::string>{"1 node ran out of battery during the run"});
  // Nodes a scripted fault killed are no battery's doing.
  json faulted = metrics(100, 0.99, 0, 0, 3);
  faulted["lifetime"]["deaths"] = {{"battery", 0}, {"fault", 3}};
  CHECK(run_warnings(faulted, 0.0).empty());
  faulted["lifetime"]["deaths"]["battery"] = 2;
  CHECK(run_warnings(faulted, 0.0) ==
        std::vector<std::string>{"2 nodes ran out of battery during the run"});
  CHECK(run_warnings(metrics(0, 1.0, 0, 0, 0), 0.0) ==
        std::vector<std::string>{"no robot completed a protocol update during the run"});
  json none = metrics(0, 1.0, 0, 0, 0);
  none["protocol"]["name"] = "none";
  CHECK(run_warnings(none, 0.0).empty());
}

TEST_CASE(
    "masnet run warns about a lossy run on the terminal and in summary.json, even with --quiet",
    "[scenarios]") {
  const fs::path base = fs::temp_directory_path() / fmt::format("masnet-warnings-{}", ::getpid());
  fs::remove_all(base);
  fs::create_directories(base);
  const auto run = [&](const std::string& name, const std::string& extra) {
    const std::string command = fmt::format(
        "'{}/scenarios/masnet' run '{}/scenarios/paper/acoustic_tracking.yaml' --quiet --out '{}' "
        "--set duration=1 "
        "--set 'output.snapshots=[]' --set output.figures=false --set output.report=false {} 2> "
        "'{}'",
        MASNET_BINARY_DIR, MASNET_SOURCE_DIR, (base / name).string(), extra,
        (base / (name + ".err")).string());
    REQUIRE(std::system(command.c_str()) == 0);
    return json::parse(masnet::test::slurp(base / name / "summary.json"))["warnings"];
  };
  const json healthy = run("healthy", "");
  CHECK(healthy == json::array());
  CHECK(masnet::test::slurp(base / "healthy.err").empty());
  const json lossy = run("lossy", "--set radio.loss=0.5");
  REQUIRE(lossy.size() >= 1);
  const std::string first = lossy[0].get<std::string>();
  CHECK(first.rfind("only ", 0) == 0);
  CHECK(masnet::test::slurp(base / "lossy.err").find("masnet: warning: " + first + "\n") == 0);
  fs::remove_all(base);
}
