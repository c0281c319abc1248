#pragma once
// Helpers the loader tests share: a scratch directory and diagnostics as text lines.
#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "scenarios/reader.hpp"

namespace masnet::test {

/// A fresh, empty directory under the system's temporary folder, removed at scope exit.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag = "loader") {
    std::string pattern =
        (std::filesystem::temp_directory_path() / ("masnet-" + tag + "-XXXXXX")).string();
    if (mkdtemp(pattern.data())) path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

/// Each diagnostic as "location: message".
inline std::vector<std::string> texts(const std::vector<scenarios::Diagnostic>& diagnostics) {
  std::vector<std::string> out;
  for (const scenarios::Diagnostic& d : diagnostics)
    out.push_back(d.text());
  return out;
}

}  // namespace masnet::test
