#pragma once
// A short run of the paper's acoustic scenario through the CLI (1 s, snapshots at 0.5 and 1 s),
// made once per test file that asks for it and removed at exit.
#include <unistd.h>

#include <fmt/format.h>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "text_files.hpp"

namespace masnet::test {

struct ShortRun {
  std::filesystem::path base, dir;
  int status = -1;
  std::string output;  // what the command printed, both streams
  /// `extra`: more command-line arguments, e.g. "--set 'domain.rectangle=[0,0,2,1]'".
  explicit ShortRun(const std::string& tag, const std::string& extra = {}) {
    namespace fs = std::filesystem;
    base = fs::temp_directory_path() / fmt::format("masnet-test-{}-{}", tag, ::getpid());
    fs::remove_all(base);
    fs::create_directories(base);
    dir = base / "run";
    const std::string command = fmt::format(
        "'{}/scenarios/masnet' run '{}/scenarios/paper/acoustic_tracking.yaml' --out '{}' --set "
        "duration=1 --set 'output.snapshots=[0.5,1]' {} > '{}' 2>&1",
        MASNET_BINARY_DIR, MASNET_SOURCE_DIR, dir.string(), extra, (base / "output.txt").string());
    status = std::system(command.c_str());
    output = slurp(base / "output.txt");
  }
  ~ShortRun() {
    std::error_code ec;
    std::filesystem::remove_all(base, ec);
  }
  ShortRun(const ShortRun&) = delete;
  ShortRun& operator=(const ShortRun&) = delete;
};

}  // namespace masnet::test
