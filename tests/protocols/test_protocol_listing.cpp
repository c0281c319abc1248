// docs/scenario-reference.md lists the built-in protocols' keys exactly as the registry declares
// them (the table `masnet protocols --markdown` prints), so the page cannot drift from the code.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "protocols/protocol_listing.hpp"

namespace mp = masnet::protocols;

namespace {

std::string documented_protocol_table() {
  std::ifstream in(std::string(MASNET_SOURCE_DIR) + "/docs/scenario-reference.md");
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str(), marker = "<!-- keys: protocol -->\n";
  const std::size_t start = page.find(marker);
  REQUIRE(start != std::string::npos);
  const std::size_t begin = start + marker.size(), end = page.find("\n\n", begin);
  return page.substr(begin, end - begin + 1);
}

}  // namespace

TEST_CASE("The scenario reference's protocol table is the built-ins' declared keys",
          "[protocols]") {
  std::vector<const mp::ProtocolDefinition*> builtins;
  for (const char* name : {"none", "radius_doubling", "oracle", "fixed_radius", "gabriel"})
    builtins.push_back(mp::find_protocol(name));
  CHECK(documented_protocol_table() == mp::protocol_table_markdown(builtins));
}

TEST_CASE("The protocol listing names each protocol and each of its keys with its range",
          "[protocols]") {
  const std::string text = mp::protocol_listing_text();
  CHECK(text.find("fixed_radius — one DISCOVER round with a constant radius\n") !=
        std::string::npos);
  CHECK(text.find("  radius           number   default 0.3        allowed > 0") !=
        std::string::npos);
  CHECK(text.find("  decay.patience   integer  default 3          allowed 0 … 1000000") !=
        std::string::npos);
}
