// A protocol under test must not see what the world knows (docs/protocol-api.md, "Ground truth
// stays out of reach"): the hosts and what a factory is given offer no true cell and no reading
// taken without a message. The installed headers are checked by tests/install/check_install.sh.
#include <catch2/catch.hpp>

#include "protocols/registry.hpp"

namespace mp = masnet::protocols;

namespace {

template <typename T>
concept offers_true_cells = requires(T& t) {
  t.true_cell(std::size_t{0});
};
template <typename T>
concept reads_sensors_without_messages = requires(T& t, mp::CentroidAccumulator& a) {
  t.read_sensors_in(mp::ConvexPolygon{}, a);
};
template <typename T>
concept hands_out_ground_truth = requires(T& t) {
  t.truth;
}
|| requires(T& t) {
  t.ground_truth;
};

// The concepts detect the members they look for (so the checks below can fail).
struct Leaky {
  std::vector<int> true_cell(std::size_t) const { return {}; }
  std::uint32_t read_sensors_in(const mp::ConvexPolygon&, mp::CentroidAccumulator&) { return 0; }
  int truth = 0;
};

}  // namespace

TEST_CASE("No host or setup a protocol is given reaches ground truth", "[protocols]") {
  STATIC_REQUIRE(offers_true_cells<Leaky>);
  STATIC_REQUIRE(reads_sensors_without_messages<Leaky>);
  STATIC_REQUIRE(hands_out_ground_truth<Leaky>);

  STATIC_REQUIRE_FALSE(offers_true_cells<mp::RobotHost>);
  STATIC_REQUIRE_FALSE(reads_sensors_without_messages<mp::RobotHost>);
  STATIC_REQUIRE_FALSE(offers_true_cells<mp::SensorHost>);
  STATIC_REQUIRE_FALSE(reads_sensors_without_messages<mp::SensorHost>);
  STATIC_REQUIRE_FALSE(hands_out_ground_truth<mp::RobotSetup>);
  STATIC_REQUIRE_FALSE(hands_out_ground_truth<mp::SensorSetup>);
  STATIC_REQUIRE_FALSE(hands_out_ground_truth<mp::ProtocolContext>);
}

TEST_CASE("Protocols registered by name: built-ins first, user protocols after, names checked",
          "[protocols]") {
  std::vector<std::string> names;
  for (const mp::ProtocolDefinition* d : mp::registered_protocols())
    names.push_back(d->name);
  REQUIRE(names.size() >= 5);
  CHECK(std::vector<std::string>(names.begin(), names.begin() + 5) ==
        std::vector<std::string>{"none", "radius_doubling", "oracle", "fixed_radius", "gabriel"});

  mp::ProtocolDefinition bad;
  bad.name = "Bad-Name";
  bad.make_robot = [](const mp::RobotSetup&) -> std::unique_ptr<mp::RobotProtocol> {
    return nullptr;
  };
  CHECK_THROWS_WITH(mp::register_protocol(bad),
                    "protocol name 'Bad-Name': use lower case letters, digits and '_'");

  mp::ProtocolDefinition taken = bad;
  taken.name = "oracle";
  CHECK_THROWS_WITH(mp::register_protocol(taken), "protocol oracle is already registered");

  mp::ProtocolDefinition clash = bad;
  clash.name = "test_clash";
  clash.params = {mp::ParamSpec::real("period", 1.0, mp::ParamRange::positive(), "s", "other")};
  CHECK_THROWS_WITH(mp::register_protocol(clash),
                    "protocol test_clash: key 'period' is declared differently by protocol "
                    "radius_doubling (one key, one meaning: choose another name)");

  mp::ProtocolDefinition fine = bad;
  fine.name = "test_fine";
  fine.params = {mp::update_period_param(),
                 mp::ParamSpec::integer("test_fanout", 3, 1, 9, "robots", "how many")};
  mp::register_protocol(fine);
  const mp::ProtocolDefinition* found = mp::find_protocol("test_fine");
  REQUIRE(found != nullptr);
  CHECK(mp::registered_protocols().back() == found);
  CHECK(found->make_sensor);  // the paper's sensors by default
  const mp::ProtocolChoice choice = mp::choose_protocol("test_fine");
  CHECK(choice.params.real("period") == 0.01);
  CHECK(choice.params.integer("test_fanout") == 3);
  CHECK_THROWS_WITH(mp::choose_protocol("test_missing"), "no protocol named 'test_missing'");
}
