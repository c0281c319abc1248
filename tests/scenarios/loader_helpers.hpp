#pragma once
// Helpers the loader tests share: a scratch directory and diagnostics as text lines.
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "scenarios/loader/reader.hpp"

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

/// A command's exit code and what it printed on its standard output.
struct Outcome {
  int exit_code = -1;
  std::string output;
};

/// Runs `command` with the shell and collects its standard output.
inline Outcome shell(const std::string& command) {
  Outcome result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
    result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace masnet::test
