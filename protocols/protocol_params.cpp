#include "protocols/protocol_params.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

namespace masnet::protocols {

ParamSpec ParamSpec::real(std::string key, double fallback, ParamRange range, std::string unit,
                          std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::real;
  s.default_value = fallback;
  s.range = range;
  s.unit = std::move(unit);
  s.meaning = std::move(meaning);
  return s;
}

ParamSpec ParamSpec::integer(std::string key, std::int64_t fallback, std::int64_t lo,
                             std::int64_t hi, std::string unit, std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::integer;
  s.default_value = fallback;
  s.range = ParamRange::between(static_cast<double>(lo), static_cast<double>(hi));
  s.unit = std::move(unit);
  s.meaning = std::move(meaning);
  return s;
}

ParamSpec ParamSpec::boolean(std::string key, bool fallback, std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::boolean;
  s.default_value = fallback;
  s.meaning = std::move(meaning);
  return s;
}

ParamSpec ParamSpec::choice(std::string key, std::string fallback, std::vector<std::string> choices,
                            std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.type = ParamType::choice;
  s.default_value = std::move(fallback);
  s.choices = std::move(choices);
  s.meaning = std::move(meaning);
  return s;
}

std::string ParamSpec::default_text() const {
  return std::visit(
      [](const auto& v) -> std::string {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, bool>)
          return v ? "true" : "false";
        else if constexpr (std::is_same_v<V, std::string>)
          return v;
        else
          return fmt::format("{}", v);
      },
      default_value);
}

std::string ParamSpec::allowed_text() const {
  switch (type) {
    case ParamType::boolean:
      return "true | false";
    case ParamType::choice:
      return fmt::format("{}", fmt::join(choices, " | "));
    case ParamType::integer:
      return fmt::format("{} … {}", static_cast<std::int64_t>(range.lo),
                         static_cast<std::int64_t>(range.hi));
    case ParamType::real:
      break;
  }
  constexpr double kUnbounded = 1e12;  // ParamRange's "no bound"
  if (range.hi >= kUnbounded) return fmt::format("{} {:g}", range.lo_open ? ">" : "≥", range.lo);
  return fmt::format("{}{:g}, {:g}{}", range.lo_open ? "(" : "[", range.lo, range.hi,
                     range.hi_open ? ")" : "]");
}

bool ParamSpec::same_declaration(const ParamSpec& o) const {
  return key == o.key && type == o.type && default_value == o.default_value &&
         range.lo == o.range.lo && range.hi == o.range.hi && range.lo_open == o.range.lo_open &&
         range.hi_open == o.range.hi_open && choices == o.choices;
}

ParamValues ParamValues::defaults(const std::vector<ParamSpec>& specs) {
  ParamValues values;
  for (const ParamSpec& spec : specs)
    values.set(spec.key, spec.default_value);
  return values;
}

void ParamValues::set(std::string_view key, ParamValue value) {
  values_.insert_or_assign(std::string(key), std::move(value));
}

const ParamValue& ParamValues::at(std::string_view key) const {
  const auto it = values_.find(key);
  if (it == values_.end())
    throw std::logic_error(fmt::format("protocol parameter '{}' was not declared", key));
  return it->second;
}

namespace {
template <class T>
const T& typed(const ParamValue& value, std::string_view key, const char* type) {
  if (const T* v = std::get_if<T>(&value)) return *v;
  throw std::logic_error(fmt::format("protocol parameter '{}' is not {}", key, type));
}
}  // namespace

double ParamValues::real(std::string_view key) const {
  return typed<double>(at(key), key, "a real number");
}
std::int64_t ParamValues::integer(std::string_view key) const {
  return typed<std::int64_t>(at(key), key, "an integer");
}
bool ParamValues::boolean(std::string_view key) const {
  return typed<bool>(at(key), key, "a boolean");
}
const std::string& ParamValues::choice(std::string_view key) const {
  return typed<std::string>(at(key), key, "a choice");
}

}  // namespace masnet::protocols
