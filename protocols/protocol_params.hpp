#pragma once
// A protocol's parameters: the keys it declares (type, default, allowed range, unit, meaning),
// which the scenario loader validates under `protocol:` and the scenario reference lists, and
// the values a run hands to the protocol (docs/protocol-api.md).
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace masnet::protocols {

enum class ParamType { real, integer, boolean, choice };

/// An interval; an open end excludes its bound.
struct ParamRange {
  double lo = -1e12, hi = 1e12;
  bool lo_open = false, hi_open = false;
  static ParamRange positive() { return {0.0, 1e12, true, false}; }
  static ParamRange non_negative() { return {0.0, 1e12, false, false}; }
  /// A duration the simulated clock can hold and that does not round to 0: [1 ns, 10^9 s].
  static ParamRange time() { return {1e-9, 1e9, false, false}; }
  static ParamRange between(double lo, double hi) { return {lo, hi, false, false}; }
};

using ParamValue = std::variant<double, std::int64_t, bool, std::string>;

/// One key under `protocol:`. A dot nests it: "decay.step" is `step` inside `decay:`.
struct ParamSpec {
  std::string key;
  ParamType type = ParamType::real;
  ParamValue default_value = 0.0;
  ParamRange range;                  ///< real and integer keys
  std::vector<std::string> choices;  ///< choice keys: the allowed names
  std::string unit;                  ///< "s", "world units", "" for none
  std::string meaning;

  static ParamSpec real(std::string key, double fallback, ParamRange range, std::string unit,
                        std::string meaning);
  static ParamSpec integer(std::string key, std::int64_t fallback, std::int64_t lo, std::int64_t hi,
                           std::string unit, std::string meaning);
  static ParamSpec boolean(std::string key, bool fallback, std::string meaning);
  static ParamSpec choice(std::string key, std::string fallback, std::vector<std::string> choices,
                          std::string meaning);
  /// The default as the reference prints it ("0.01", "true", "to_2d").
  std::string default_text() const;
  /// The allowed values as `masnet protocols` prints them ("> 0", "[1e-09, 1e+09]",
  /// "0 … 1000000", "to_2d | double").
  std::string allowed_text() const;
  bool same_declaration(const ParamSpec& other) const;
};

/// The values of one run's protocol keys. Reading a key the protocol did not declare, or with
/// the wrong type, is a programming error: it throws std::logic_error naming the key.
class ParamValues {
 public:
  /// Every key at its default.
  static ParamValues defaults(const std::vector<ParamSpec>& specs);

  void set(std::string_view key, ParamValue value);
  bool has(std::string_view key) const { return values_.count(std::string(key)) != 0; }
  double real(std::string_view key) const;
  std::int64_t integer(std::string_view key) const;
  bool boolean(std::string_view key) const;
  const std::string& choice(std::string_view key) const;
  const std::map<std::string, ParamValue, std::less<>>& all() const { return values_; }

 private:
  const ParamValue& at(std::string_view key) const;
  std::map<std::string, ParamValue, std::less<>> values_;
};

}  // namespace masnet::protocols
