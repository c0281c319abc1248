// How a fuzz input is split into the scenario text and its --set strings (fuzz_input.hpp).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "fuzz_input.hpp"

using masnet::fuzz::split_fuzz_input;
using Strings = std::vector<std::string>;

TEST_CASE("An input without the separator is all scenario text", "[fuzz]") {
  const auto input = split_fuzz_input("duration: 5\n--set-ish: 1\n");
  CHECK(input.yaml_text == "duration: 5\n--set-ish: 1\n");
  CHECK(input.overrides.empty());
}

TEST_CASE("Each separator starts one --set string, the text before the first is the file",
          "[fuzz]") {
  const auto input = split_fuzz_input("duration: 5\n--set radio.loss=0.2\n--set seed=3");
  CHECK(input.yaml_text == "duration: 5");
  CHECK(input.overrides == Strings{"radio.loss=0.2", "seed=3"});
}

TEST_CASE("Empty pieces stay: an empty file and an empty --set string", "[fuzz]") {
  const auto input = split_fuzz_input("\n--set \n--set duration=1");
  CHECK(input.yaml_text.empty());
  CHECK(input.overrides == Strings{"", "duration=1"});
}

TEST_CASE("A fourth separator and what follows stay inside the third --set string", "[fuzz]") {
  const auto input = split_fuzz_input("x: 1\n--set a=1\n--set b=2\n--set c=3\n--set d=4");
  CHECK(input.yaml_text == "x: 1");
  CHECK(input.overrides == Strings{"a=1", "b=2", "c=3\n--set d=4"});
}

TEST_CASE("NUL bytes are kept in both parts", "[fuzz]") {
  const std::string data("a\0b\n--set c\0d", 13);
  const auto input = split_fuzz_input(data);
  CHECK(input.yaml_text == std::string("a\0b", 3));
  CHECK(input.overrides == Strings{std::string("c\0d", 3)});
}
