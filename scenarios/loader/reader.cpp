#include "scenarios/loader/reader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace masnet::scenarios {

ScenarioReader::ScenarioReader(std::string file_name,
                               std::vector<std::pair<std::string, std::string>> overrides)
    : file_name_(std::move(file_name)), overrides_(std::move(overrides)) {}

std::string ScenarioReader::location(const YAML::Node& node, const std::string& path) const {
  // A value that came from the command line is located there, not in the file.
  for (const auto& [override_path, text] : overrides_)
    if (path == override_path || path.rfind(override_path + ".", 0) == 0 ||
        path.rfind(override_path + "[", 0) == 0)
      return "--set " + shown_text(text);
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) {
    // A node without a mark was created by an override of a key below it (--set groups.x=1).
    for (const auto& [override_path, text] : overrides_)
      if (override_path.rfind(path + ".", 0) == 0) return "--set " + shown_text(text);
    return file_name_ + ":1:1";
  }
  return file_name_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

void ScenarioReader::warning(std::string location, std::string message) {
  warnings_.push_back({std::move(location), std::move(message)});
}

void ScenarioReader::note_known(const std::string& path) {
  std::string generic;
  generic.reserve(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    generic.push_back(path[i]);
    if (path[i] != '[') continue;
    while (i + 1 < path.size() && path[i + 1] != ']')
      ++i;  // drop the index
  }
  known_paths_.insert(std::move(generic));
}

void Section::note(std::string_view key) {
  known_.emplace(key);
  reader_->note_known(child_path(key));
}

void ScenarioReader::error(std::string location, std::string message) {
  diagnostics_.push_back({std::move(location), std::move(message)});
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe(double v) const {
  auto num = [](double x) {
    std::ostringstream out;
    out << x;
    return out.str();
  };
  const bool has_lo = lo > -kMaxMagnitude, has_hi = hi < kMaxMagnitude;
  std::string lower = lo == 0.0 ? (lo_open ? "> 0" : ">= 0") : (lo_open ? "> " : ">= ") + num(lo);
  // A time: "> 0" unless the value is positive but shorter than the clock's resolution.
  if (lo == kMinTime_s)
    lower = v > 0.0 && v < lo ? ">= 1e-09 (1 ns, the clock's resolution)" : "> 0";
  const std::string upper = (hi_open ? "< " : "<= ") + num(hi);
  // Bounds at the time and magnitude caps are limits, not the key's natural range: the message
  // names the one that was passed.
  const bool natural_hi = hi < kMaxTime_s;
  std::string bounds;
  if (has_lo && has_hi && natural_hi && lo != kMinTime_s)
    bounds = std::string("in ") + (lo_open ? "(" : "[") + num(lo) + ", " + num(hi) +
             (hi_open ? ")" : "]");
  else if (std::isfinite(v) && v > hi)
    bounds = upper;  // past a cap
  else if (has_lo)
    bounds = lower;
  else if (has_hi)
    bounds = upper;
  else
    bounds = "in [" + num(lo) + ", " + num(hi) + "]";
  return std::isfinite(v) ? bounds : "finite and " + bounds;
}

std::size_t utf8_sequence_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned min_second = 0x80, max_second = 0xBF;  // the second byte's range (RFC 3629)
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) min_second = 0xA0;  // overlong
    if (lead == 0xED) max_second = 0x9F;  // surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) min_second = 0x90;  // overlong
    if (lead == 0xF4) max_second = 0x8F;  // beyond U+10FFFF
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  if (byte(at + 1) < min_second || byte(at + 1) > max_second) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(at + k) < 0x80 || byte(at + k) > 0xBF) return 0;
  return length;
}

std::size_t first_invalid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

std::string shown_text(std::string_view text) {
  constexpr std::size_t kMaxShown = 80;  // characters, an escape counting as its four
  std::string out;
  std::size_t shown = 0, i = 0;
  while (i < text.size() && shown < kMaxShown) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_sequence_length(text, i);
    if (n == 0 || c < 0x20 || c == 0x7F) {
      static const char* hex = "0123456789ABCDEF";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
      shown += 4;
      ++i;
    } else {
      out.append(text.substr(i, n));
      ++shown;
      i += n;
    }
  }
  if (i < text.size()) out += "… (" + std::to_string(text.size()) + " bytes in all)";
  return out;
}

Section::Section(ScenarioReader& reader, YAML::Node node, std::string path, std::string pointer)
    : reader_(&reader),
      node_(std::move(node)),
      path_(std::move(path)),
      pointer_(std::move(pointer)) {}

std::string Section::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

YAML::Node Section::key_node(std::string_view key) const {
  if (!node_ || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) return it->first;
  return YAML::Node(YAML::NodeType::Undefined);
}

YAML::Node Section::child(std::string_view key) const {
  if (!node_ || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) return it->second;
  return YAML::Node(YAML::NodeType::Undefined);
}

bool Section::has(std::string_view key) const {
  return child(key).IsDefined();
}

std::string Section::where() const {
  return reader_->location(node_, path_);
}

std::string Section::where(std::string_view key) const {
  const YAML::Node value = child(key);
  if (!value.IsDefined()) return where();
  return reader_->location(value.IsNull() ? key_node(key) : value, child_path(key));
}

void Section::error_at(std::string_view key, const std::string& message) {
  reader_->error(where(key), child_path(key) + ": " + message);
}

void Section::warn_at(std::string_view key, const std::string& message) {
  reader_->warning(where(key), child_path(key) + ": " + message);
}

void Section::resolve(std::string_view key, nlohmann::json value) {
  reader_->resolved()[nlohmann::json::json_pointer(pointer_ + "/" + std::string(key))] =
      std::move(value);
}

namespace {
std::string shown(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + shown_text(node.Scalar()) + "'";
  if (node.IsSequence()) {
    // A short list of scalars is shown as written ("[1, 2, 3]"): "got a list" would puzzle
    // someone who was asked for a point, which is a list too.
    std::string items;
    for (const auto& item : node) {
      if (!item.IsScalar()) return "a list of " + std::to_string(node.size()) + " items";
      items += (items.empty() ? "" : ", ") + item.Scalar();
    }
    if (items.size() <= 40) return "[" + shown_text(items) + "]";
    return "a list of " + std::to_string(node.size()) + " items";
  }
  if (node.IsMap()) return "a mapping";
  return "nothing (null)";
}
}  // namespace

double Section::number(std::string_view key, double fallback, Range range) {
  note(key);
  const YAML::Node value = child(key);
  double result = fallback;
  if (value.IsDefined()) {
    double parsed = 0.0;
    if (!value.IsScalar() || !YAML::convert<double>::decode(value, parsed)) {
      error_at(key, "expected a number, got " + shown(value));
    } else if (!range.contains(parsed)) {
      error_at(key,
               "must be " + range.describe(parsed) + " (got " + shown_text(value.Scalar()) + ")");
    } else {
      result = parsed;
    }
  }
  resolve(key, result);
  return result;
}

std::int64_t Section::integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                              std::int64_t hi) {
  note(key);
  const YAML::Node value = child(key);
  std::int64_t result = fallback;
  if (value.IsDefined()) {
    long long parsed = 0;
    if (!value.IsScalar() || !YAML::convert<long long>::decode(value, parsed)) {
      error_at(key, "expected a whole number, got " + shown(value));
    } else if (parsed < lo || parsed > hi) {
      error_at(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi) +
                        " (got " + shown_text(value.Scalar()) + ")");
    } else {
      result = parsed;
    }
  }
  resolve(key, result);
  return result;
}

bool Section::boolean(std::string_view key, bool fallback) {
  note(key);
  const YAML::Node value = child(key);
  bool result = fallback;
  if (value.IsDefined()) {
    bool parsed = false;
    if (!value.IsScalar() || !YAML::convert<bool>::decode(value, parsed))
      error_at(key, "expected true or false, got " + shown(value));
    else
      result = parsed;
  }
  resolve(key, result);
  return result;
}

std::string Section::text(std::string_view key, std::string fallback) {
  note(key);
  const YAML::Node value = child(key);
  std::string result = std::move(fallback);
  if (value.IsDefined()) {
    if (!value.IsScalar())
      error_at(key, "expected a text, got " + shown(value));
    else
      result = value.Scalar();
  }
  resolve(key, result);
  return result;
}

std::string Section::choose(std::string_view key, const std::vector<std::string>& names,
                            const std::string& fallback) {
  note(key);
  const YAML::Node value = child(key);
  std::string result = fallback;
  if (value.IsDefined()) {
    if (!value.IsScalar() || std::find(names.begin(), names.end(), value.Scalar()) == names.end()) {
      std::string list;
      for (const auto& n : names)
        list += (list.empty() ? "" : ", ") + n;
      std::string message = "expected one of " + list + ", got " + shown(value);
      if (value.IsScalar())
        if (auto guess = closest(value.Scalar(), names))
          message += " (did you mean '" + *guess + "'?)";
      error_at(key, message);
    } else {
      result = value.Scalar();
    }
  }
  resolve(key, result);
  return result;
}

namespace {
bool decode_point(const YAML::Node& node, Vec2& out) {
  if (!node.IsSequence() || node.size() != 2) return false;
  double x = 0, y = 0;
  if (!node[0].IsScalar() || !node[1].IsScalar()) return false;
  if (!YAML::convert<double>::decode(node[0], x) || !YAML::convert<double>::decode(node[1], y))
    return false;
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  out = Vec2{x, y};
  return true;
}
nlohmann::json json_point(const Vec2& p) {
  return nlohmann::json::array({p.x(), p.y()});
}
}  // namespace

namespace {

// Coordinates and velocities beyond kMaxMagnitude overflow downstream (start + velocity·t,
// squared distances): they are an error like a value that is not a point.
std::string point_problem(const YAML::Node& node, Vec2& out) {
  if (!decode_point(node, out)) return "expected a point [x, y], got " + shown(node);
  if (!(std::fabs(out.x()) <= kMaxMagnitude && std::fabs(out.y()) <= kMaxMagnitude))
    return "coordinates must be within ±1e+12, got " + shown(node);
  return "";
}

}  // namespace

Vec2 Section::point(std::string_view key, Vec2 fallback) {
  note(key);
  const YAML::Node value = child(key);
  Vec2 result = fallback;
  if (value.IsDefined()) {
    Vec2 parsed;
    if (std::string problem = point_problem(value, parsed); !problem.empty())
      error_at(key, problem);
    else
      result = parsed;
  }
  resolve(key, json_point(result));
  return result;
}

std::vector<Vec2> Section::points(std::string_view key, std::size_t min_count) {
  note(key);
  const YAML::Node value = child(key);
  std::vector<Vec2> result;
  if (value.IsDefined()) {
    if (!value.IsSequence()) {
      error_at(key, "expected a list of points [[x, y], ...], got " + shown(value));
    } else {
      for (std::size_t i = 0; i < value.size(); ++i) {
        Vec2 p;
        if (std::string problem = point_problem(value[i], p); !problem.empty()) {
          reader_->error(reader_->location(value[i], child_path(key)),
                         child_path(key) + "[" + std::to_string(i) + "]: " + problem);
          continue;
        }
        result.push_back(p);
      }
      if (result.size() < min_count)
        error_at(key, "needs at least " + std::to_string(min_count) + " points (got " +
                          std::to_string(result.size()) + ")");
    }
  }
  nlohmann::json list = nlohmann::json::array();
  for (const Vec2& p : result)
    list.push_back(json_point(p));
  resolve(key, list);
  return result;
}

std::vector<double> Section::numbers(std::string_view key, Range range) {
  note(key);
  const YAML::Node value = child(key);
  std::vector<double> result;
  if (value.IsDefined()) {
    if (!value.IsSequence()) {
      error_at(key, "expected a list of numbers, got " + shown(value));
    } else {
      for (std::size_t i = 0; i < value.size(); ++i) {
        double x = 0;
        const std::string item = child_path(key) + "[" + std::to_string(i) + "]";
        if (!value[i].IsScalar() || !YAML::convert<double>::decode(value[i], x)) {
          reader_->error(reader_->location(value[i], child_path(key)),
                         item + ": expected a number, got " + shown(value[i]));
        } else if (!range.contains(x)) {
          reader_->error(reader_->location(value[i], child_path(key)),
                         item + ": must be " + range.describe(x) + " (got " +
                             shown_text(value[i].Scalar()) + ")");
        } else {
          result.push_back(x);
        }
      }
    }
  }
  resolve(key, result);
  return result;
}

std::vector<std::int64_t> Section::distinct_integers(std::string_view key, std::int64_t lo,
                                                     std::int64_t hi, const std::string& what) {
  note(key);
  const YAML::Node value = child(key);
  std::vector<std::int64_t> result;
  if (value.IsDefined()) {
    if (!value.IsSequence()) {
      error_at(key, "expected a list of whole numbers, got " + shown(value));
    } else {
      std::map<std::int64_t, std::size_t> first_item;  // each number's first place in the list
      for (std::size_t i = 0; i < value.size(); ++i) {
        long long x = 0;
        const std::string item = child_path(key) + "[" + std::to_string(i) + "]";
        const std::string at = reader_->location(value[i], child_path(key));
        if (!value[i].IsScalar() || !YAML::convert<long long>::decode(value[i], x)) {
          reader_->error(at, item + ": expected a whole number, got " + shown(value[i]));
        } else if (x < lo || x > hi) {
          reader_->error(at, item + ": there is no " + what + " " + std::to_string(x) + " (" +
                                 what + "s are numbered " + std::to_string(lo) + " to " +
                                 std::to_string(hi) + ")");
        } else if (const auto [first, inserted] = first_item.emplace(x, i); !inserted) {
          reader_->error(at, item + ": " + what + " " + std::to_string(x) +
                                 " is listed twice (first as item " +
                                 std::to_string(first->second) + ")");
        } else {
          result.push_back(x);
        }
      }
    }
  }
  resolve(key, result);
  return result;
}

Section Section::section(std::string_view key) {
  note(key);
  YAML::Node value = child(key);
  const std::string path = child_path(key);
  const std::string pointer = pointer_ + "/" + std::string(key);
  if (value.IsDefined() && !value.IsMap()) {
    error_at(key, "expected a mapping of keys, got " + shown(value));
    value = YAML::Node(YAML::NodeType::Undefined);
  }
  reader_->resolved()[nlohmann::json::json_pointer(pointer)] = nlohmann::json::object();
  return Section(*reader_, value, path, pointer);
}

std::vector<Section> Section::sections(std::string_view key) {
  note(key);
  const YAML::Node value = child(key);
  std::vector<Section> result;
  const std::string pointer = pointer_ + "/" + std::string(key);
  reader_->resolved()[nlohmann::json::json_pointer(pointer)] = nlohmann::json::array();
  if (!value.IsDefined()) return result;
  if (!value.IsSequence()) {
    error_at(key, "expected a list, got " + shown(value));
    return result;
  }
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string path = child_path(key) + "[" + std::to_string(i) + "]";
    if (!value[i].IsMap()) {
      reader_->error(reader_->location(value[i], child_path(key)),
                     path + ": expected a mapping of keys, got " + shown(value[i]));
      continue;
    }
    const std::string item_pointer = pointer + "/" + std::to_string(result.size());
    reader_->resolved()[nlohmann::json::json_pointer(item_pointer)] = nlohmann::json::object();
    result.emplace_back(*reader_, value[i], path, item_pointer);
  }
  return result;
}

void Section::reject(std::string_view key, const std::string& why) {
  note(key);
  if (has(key)) error_at(key, why);
}

void Section::finish() {
  if (!node_ || !node_.IsMap()) return;
  std::vector<std::string> known(known_.begin(), known_.end());
  std::map<std::string, int, std::less<>> first_line;  // 1-based line of each key's first use
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.IsScalar() ? it->first.Scalar() : std::string("?");
    // yaml-cpp keeps both copies of a repeated key and the accessors read the first: the
    // second value would be ignored without a word.
    if (it->first.IsScalar()) {
      const auto [first, inserted] = first_line.emplace(key, it->first.Mark().line + 1);
      if (!inserted) {
        reader_->error(reader_->location(it->first, child_path(key)),
                       "duplicate key '" + shown_text(key) + "'" +
                           (path_.empty() ? std::string() : " in '" + path_ + "'") +
                           " (first given on line " + std::to_string(first->second) + ")");
        continue;
      }
    }
    if (known_.count(key)) continue;
    std::string message = "unknown key '" + shown_text(key) + "'" +
                          (path_.empty() ? std::string() : " in '" + path_ + "'");
    if (auto guess = closest(key, known)) message += " (did you mean '" + *guess + "'?)";
    reader_->error(reader_->location(it->first, child_path(key)), message);
  }
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::optional<std::string> closest(std::string_view word,
                                   const std::vector<std::string>& candidates) {
  // A plausible typo: at most a third of the word wrong (and at least one edit allowed).
  const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const auto& c : candidates) {
    // The distance is at least the difference in length: a megabyte key costs nothing.
    const std::size_t longer = std::max(word.size(), c.size()),
                      shorter = std::min(word.size(), c.size());
    if (longer - shorter > allowed) continue;
    const std::size_t d = edit_distance(word, c);
    if (!best || d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  if (best && best_distance <= allowed) return best;
  return std::nullopt;
}

}  // namespace masnet::scenarios
