#pragma once
// Small helpers the scenario tests share for looking at what a run wrote.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace masnet::test {

/// The whole file as bytes ("" if it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// How often `what` occurs in `text`, without overlaps.
inline std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos;
       at = text.find(what, at + what.size()))
    ++n;
  return n;
}

}  // namespace masnet::test
