#pragma once
// Input that has not been parsed yet: files read with a size cap, YAML text checked before it is
// loaded (UTF-8, one document, no tags, bounded aliases), and names that become paths. The
// limits are documented in docs/scenario-reference.md ("Limits").
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scenarios/loader/reader.hpp"

namespace masnet::scenarios {

/// A scenario or sweep file is at most 16 MiB: more is no hand-written scenario.
inline constexpr std::uint64_t kMaxScenarioFileBytes = std::uint64_t{16} << 20;
/// A sensor file is at most 1 GiB (10^7 sensors take about 400 MB of text).
inline constexpr std::uint64_t kMaxSensorFileBytes = std::uint64_t{1} << 30;
/// YAML aliases (*name) may repeat at most this many nodes in all: yaml-cpp shares an aliased
/// node, but every reader walks each repetition, so a few lines can stand for billions.
inline constexpr std::uint64_t kMaxAliasNodes = 100'000;
/// The longest name (scenario names become run directories).
inline constexpr std::size_t kMaxNameChars = 64;

/// Reads `path` if it is a regular file of at most `max_bytes`. On failure returns false and
/// sets `problem` to the reason: the system's ("No such file or directory"), "not a regular
/// file", or the size. Never blocks on a FIFO, never reads past the cap.
bool read_regular_file(const std::string& path, std::uint64_t max_bytes, std::string& text,
                       std::string& problem);

/// "LINE:COL" (1-based, columns in bytes like yaml-cpp's) of byte `offset` of `text`.
std::string line_column(std::string_view text, std::size_t offset);

/// Checks YAML text before it is loaded: valid UTF-8, a single document, no tags (!!str, !foo),
/// aliases within kMaxAliasNodes. `where` prefixes every location: "file.yaml" gives
/// "file.yaml:LINE:COL"; an empty `file` locates everything at `fixed_location` instead (a
/// --set value). YAML syntax errors are left to the loader.
std::vector<Diagnostic> check_yaml_text(const std::string& text, const std::string& file,
                                        const std::string& fixed_location = "");

/// A name that is safe as a file name: 1 to 64 of A-Z a-z 0-9 . _ -, not starting with '.' or
/// '-'.
bool valid_name(std::string_view name);
/// What valid_name requires, for messages.
std::string name_rule();
/// `text` made a valid name: other characters become '_', leading '.' and '-' are dropped, cut
/// at 64 characters; "scenario" when nothing is left.
std::string sanitized_name(std::string_view text);

}  // namespace masnet::scenarios
