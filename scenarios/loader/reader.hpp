#pragma once
// Reading a YAML scenario with positions: every value is read through a
// Section, which knows its dotted path and its file position, checks type and range, records
// the resolved value (defaults included) for summary.json, and reports unknown keys with a
// "did you mean" suggestion. Errors are collected, never thrown through the model.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

#include "net/vec2.hpp"

namespace masnet::scenarios {

using net::Vec2;

/// One problem with the input, printed as "location: message".
struct Diagnostic {
  std::string location;  ///< "file:line:col" or "--set a.b=v"
  std::string message;
  std::string text() const { return location + ": " + message; }
};

/// Collects diagnostics and the resolved values of one scenario file.
class ScenarioReader {
 public:
  /// `overrides` maps each dotted path given with --set to its "a.b=v" text.
  ScenarioReader(std::string file_name, std::vector<std::pair<std::string, std::string>> overrides);

  const std::string& file_name() const { return file_name_; }
  /// Location of `node` (at `path`), for messages.
  std::string location(const YAML::Node& node, const std::string& path) const;
  void error(std::string location, std::string message);

  /// A problem that does not stop the run (a key that does not apply here).
  void warning(std::string location, std::string message);

  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  bool ok() const { return diagnostics_.empty(); }
  nlohmann::json& resolved() { return resolved_; }

  /// Records that the loader knows the key at dotted `path` (read, or rejected for this
  /// scenario's kinds); list indices become "[]": "field.targets[].start".
  void note_known(const std::string& path);
  /// Every key path noted so far: what the scenario reference must document.
  const std::set<std::string>& known_paths() const { return known_paths_; }

 private:
  std::string file_name_;
  std::vector<std::pair<std::string, std::string>> overrides_;
  std::vector<Diagnostic> diagnostics_, warnings_;
  std::set<std::string> known_paths_;
  nlohmann::json resolved_ = nlohmann::json::object();
};

/// The largest magnitude a number of the scenario may have (docs/scenario-reference.md,
/// "Limits"): positions, speeds and amplitudes beyond it overflow downstream (squared distances,
/// positions after a long run).
inline constexpr double kMaxMagnitude = 1e12;
/// The longest time in seconds (durations, periods, delays): about 31.7 years, so that sums of
/// a few times stay inside the integer-nanosecond clock (±292 years).
inline constexpr double kMaxTime_s = 1e9;
/// The shortest positive time: the clock's resolution (shorter periods would round to 0).
inline constexpr double kMinTime_s = 1e-9;

/// A closed interval check for numbers; `lo_open`/`hi_open` exclude an end. Unbounded ends stop
/// at ±kMaxMagnitude.
struct Range {
  double lo = -kMaxMagnitude, hi = kMaxMagnitude;
  bool lo_open = false, hi_open = false;
  static Range positive() { return {0.0, kMaxMagnitude, true, false}; }
  static Range non_negative() { return {0.0, kMaxMagnitude, false, false}; }
  static Range unit() { return {0.0, 1.0, false, false}; }
  /// A time that the clock can hold and that does not round to 0: [1 ns, 10^9 s].
  static Range time() { return {kMinTime_s, kMaxTime_s, false, false}; }
  /// A delay that may be 0: [0, 10^9 s].
  static Range delay() { return {0.0, kMaxTime_s, false, false}; }
  bool contains(double v) const;
  /// What `v` breaks: "> 0", "in [0, 1)", "<= 1e+12", "finite and > 0".
  std::string describe(double v) const;
};

/// A value as messages show it: non-printable bytes and bytes that are not UTF-8 as \xNN, and
/// at most 80 characters, longer values cut with "…" and their length. Every value or key a
/// message echoes goes through here (raw bytes would reach the terminal).
std::string shown_text(std::string_view text);
/// The length of the UTF-8 sequence starting at `at`, or 0 if the bytes there are not UTF-8.
std::size_t utf8_sequence_length(std::string_view text, std::size_t at);
/// The offset of the first byte that is not UTF-8, or npos.
std::size_t first_invalid_utf8(std::string_view text);

/// A YAML mapping at a dotted path. Accessors return the value or the fallback (when the key
/// is absent or bad), and remember the key as known for `finish()`. A key given with no value
/// (null) is an error, never the default: `duration:` is not a duration.
class Section {
 public:
  Section(ScenarioReader& reader, YAML::Node node, std::string path, std::string pointer);

  const std::string& path() const { return path_; }
  ScenarioReader& reader() const { return *reader_; }
  bool has(std::string_view key) const;
  /// The mapping at `key` for locating messages only: nothing is resolved or marked known.
  Section peek(std::string_view key) const {
    return Section(*reader_, child(key), child_path(key), pointer_ + "/" + std::string(key));
  }
  /// Location of `key`'s value, or of the section itself when absent.
  std::string where(std::string_view key) const;
  std::string where() const;
  void error_at(std::string_view key, const std::string& message);
  /// A warning at `key`'s value (the run goes on).
  void warn_at(std::string_view key, const std::string& message);

  double number(std::string_view key, double fallback, Range range = {});
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi);
  bool boolean(std::string_view key, bool fallback);
  std::string text(std::string_view key, std::string fallback);
  /// One of `options` (by name); the message lists them all when the value is not one.
  template <class E>
  E choice(std::string_view key, E fallback,
           std::initializer_list<std::pair<std::string_view, E>> options) {
    std::vector<std::string> names;
    for (const auto& [name, value] : options)
      names.emplace_back(name);
    const std::string picked = choose(key, names, fallback_name(options, fallback));
    for (const auto& [name, value] : options)
      if (name == picked) return value;
    return fallback;
  }
  /// One of `names`; the message lists them all when the value is not one.
  std::string choice_of(std::string_view key, const std::vector<std::string>& names,
                        const std::string& fallback) {
    return choose(key, names, fallback);
  }
  Vec2 point(std::string_view key, Vec2 fallback);
  /// A list of [x, y] points; `min_count` checked.
  std::vector<Vec2> points(std::string_view key, std::size_t min_count = 0);
  std::vector<double> numbers(std::string_view key, Range range = {});
  /// A list of whole numbers, each in [lo, hi]; `what` names one in messages ("robot"), and
  /// a number listed twice is an error.
  std::vector<std::int64_t> distinct_integers(std::string_view key, std::int64_t lo,
                                              std::int64_t hi, const std::string& what);
  /// A nested mapping (an empty one if absent).
  Section section(std::string_view key);
  /// A list of mappings.
  std::vector<Section> sections(std::string_view key);
  /// Marks `key` as known without reading it (read only in some cases, e.g. an alias).
  void mark_known(std::string_view key) { note(key); }
  /// Marks `key` as known but reports it if present (it does not apply here).
  void reject(std::string_view key, const std::string& why);
  /// Reports every key that no accessor asked for.
  void finish();

  /// Records a resolved value computed by the builder (e.g. a derived default).
  void resolve(std::string_view key, nlohmann::json value);

 private:
  template <class E>
  static std::string fallback_name(std::initializer_list<std::pair<std::string_view, E>> options,
                                   E fallback) {
    for (const auto& [name, value] : options)
      if (value == fallback) return std::string(name);
    return {};
  }
  std::string choose(std::string_view key, const std::vector<std::string>& names,
                     const std::string& fallback);
  std::string child_path(std::string_view key) const;
  YAML::Node child(std::string_view key) const;
  /// The key's own node (for locating a null value, which yaml-cpp marks on the next line).
  YAML::Node key_node(std::string_view key) const;

  ScenarioReader* reader_;
  YAML::Node node_;
  std::string path_;     // dotted, for messages: "field.targets[1]"
  std::string pointer_;  // JSON pointer into the resolved scenario: "/field/targets/1"
  std::set<std::string, std::less<>> known_;
  void note(std::string_view key);
};

/// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);
/// The closest of `candidates` to `word`, if close enough to be a plausible typo.
std::optional<std::string> closest(std::string_view word,
                                   const std::vector<std::string>& candidates);

}  // namespace masnet::scenarios
