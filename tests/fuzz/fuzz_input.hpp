#pragma once
// How one fuzz input becomes a scenario text and its --set strings (docs/testing.md): the bytes
// before the first "\n--set " are the YAML text, each later piece is one --set string. At most
// three --set strings are made; a fourth separator and what follows stay in the third string.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace masnet::fuzz {

inline constexpr std::string_view kSetSeparator = "\n--set ";
inline constexpr std::size_t kMaxOverrides = 3;

struct FuzzInput {
  std::string yaml_text;
  std::vector<std::string> overrides;
};

inline FuzzInput split_fuzz_input(std::string_view data) {
  FuzzInput input;
  std::size_t cut = data.find(kSetSeparator);
  input.yaml_text = std::string(data.substr(0, cut));
  while (cut != std::string_view::npos) {
    const std::size_t start = cut + kSetSeparator.size();
    cut = input.overrides.size() + 1 < kMaxOverrides ? data.find(kSetSeparator, start)
                                                     : std::string_view::npos;
    input.overrides.emplace_back(
        data.substr(start, cut == std::string_view::npos ? cut : cut - start));
  }
  return input;
}

}  // namespace masnet::fuzz
