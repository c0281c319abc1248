#pragma once
// Helpers the sweep tests share: a scratch directory, sweep files written on the fly, and the
// runs table of results.sqlite read back.
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <sqlite3.h>

#include <catch2/catch.hpp>

#include "scenarios/sweep/sweep.hpp"

namespace masnet::test {

inline const std::string kSweepBase =
    std::string(MASNET_SOURCE_DIR) + "/scenarios/paper/acoustic_tracking.yaml";

// A tiny acoustic run: 0.2 s, 20 × 20 sensors, no snapshots (≈ 0.05 s each).
inline const char* const kTinySet =
    "set: {duration: 0.2, sensors.nx: 20, sensors.ny: 20, output.snapshots: [], output.updates: "
    "false}\n";

/// The diagnostics of a sweep text that must not load (as `file:line:col: message`), the text
/// read as if it were the file `file_name`.
inline std::vector<std::string> sweep_errors(const std::string& text,
                                             const std::string& file_name) {
  scenarios::SweepLoad loaded = scenarios::load_sweep_text(text, file_name);
  CHECK_FALSE(loaded.sweep);
  std::vector<std::string> lines;
  for (const auto& d : loaded.diagnostics)
    lines.push_back(d.text());
  return lines;
}

/// An empty path under the temporary folder for one test (removed first if it exists).
inline std::filesystem::path fresh_dir(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("masnet-test-sweep-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

/// Writes `text` to `path`, creating its folder; returns the path.
inline std::filesystem::path write_file(const std::filesystem::path& path,
                                        const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

/// A sweep of the tiny acoustic run over two seeds, with `extra` (vary, variants...) appended.
inline std::string tiny_sweep_text(const std::string& extra) {
  return "base: " + kSweepBase + "\nseeds: 2\n" + kTinySet + extra;
}

using Row = std::map<std::string, std::string>;

// The `runs` table by run_index, every column as text, wall-clock columns left out.
inline std::vector<Row> runs_table(const std::filesystem::path& dir) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2((dir / "results.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr) ==
          SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, "SELECT * FROM runs ORDER BY run_index", -1, &stmt, nullptr) ==
          SQLITE_OK);
  std::vector<Row> rows;
  while (sqlite3_step(stmt) == SQLITE_ROW) {
    Row row;
    for (int c = 0; c < sqlite3_column_count(stmt); ++c) {
      const std::string name = sqlite3_column_name(stmt, c);
      if (name == "wall_time_s" || name == "finished_at") continue;
      const unsigned char* text = sqlite3_column_text(stmt, c);
      row[name] = text ? reinterpret_cast<const char*>(text) : "NULL";
    }
    rows.push_back(std::move(row));
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return rows;
}

inline std::size_t count_rows(const std::filesystem::path& dir, const std::string& sql) {
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2((dir / "results.sqlite").c_str(), &db, SQLITE_OPEN_READONLY, nullptr) ==
          SQLITE_OK);
  sqlite3_stmt* stmt = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) == SQLITE_OK);
  REQUIRE(sqlite3_step(stmt) == SQLITE_ROW);
  const auto n = static_cast<std::size_t>(sqlite3_column_int64(stmt, 0));
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return n;
}

}  // namespace masnet::test
