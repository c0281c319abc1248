// The `protocol` section, read from the registry's declarations: the built-ins' keys and a
// program's own protocols' keys are checked the same way (docs/protocol-api.md).
#include <map>

#include "scenarios/loader/scenario_parts.hpp"

namespace masnet::scenarios {
namespace {

std::string top_key(const std::string& key) {
  return key.substr(0, key.find('.'));
}

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

protocols::ParamValue read_value(Section& s, const std::string& key,
                                 const protocols::ParamSpec& spec) {
  using protocols::ParamType;
  switch (spec.type) {
    case ParamType::real: {
      const Range range{spec.range.lo, spec.range.hi, spec.range.lo_open, spec.range.hi_open};
      return s.number(key, std::get<double>(spec.default_value), range);
    }
    case ParamType::integer:
      return s.integer(key, std::get<std::int64_t>(spec.default_value),
                       static_cast<std::int64_t>(spec.range.lo),
                       static_cast<std::int64_t>(spec.range.hi));
    case ParamType::boolean:
      return s.boolean(key, std::get<bool>(spec.default_value));
    case ParamType::choice:
      return s.choice_of(key, spec.choices, std::get<std::string>(spec.default_value));
  }
  return spec.default_value;
}

}  // namespace

double default_reply_timeout_s(net::RadioLevel level) {
  return level == net::RadioLevel::csma ? 0.008 : 0.002;
}

protocols::ProtocolChoice read_protocol(Section s, net::RadioLevel level) {
  const std::vector<const protocols::ProtocolDefinition*> all = protocols::registered_protocols();
  std::vector<std::string> names;
  for (const auto* d : all)
    names.push_back(d->name);
  protocols::ProtocolChoice choice;
  choice.kind = s.choice_of("kind", names, std::string(protocols::kDefaultProtocol));
  const protocols::ProtocolDefinition* chosen = protocols::find_protocol(choice.kind);
  choice.params = protocols::ParamValues{};

  // Every protocol's keys, in registration order: a key of another kind is still checked (a
  // sweep may vary the kind under a fixed set of keys), and resolved with its default.
  std::vector<std::string> tops;                          // top-level keys, first seen first
  std::map<std::string, std::vector<std::string>> kinds;  // top-level key -> kinds declaring it
  std::map<std::string, Section> nested;
  std::vector<std::string> read;
  for (const auto* d : all)
    for (const protocols::ParamSpec& spec : d->params) {
      const std::string top = top_key(spec.key);
      if (!kinds.count(top)) tops.push_back(top);
      auto& declaring = kinds[top];
      if (declaring.empty() || declaring.back() != d->name) declaring.push_back(d->name);
      if (std::find(read.begin(), read.end(), spec.key) != read.end()) continue;
      read.push_back(spec.key);
      protocols::ParamValue value;
      if (spec.key == "reply_timeout") {
        protocols::ParamSpec per_level = spec;
        per_level.default_value = default_reply_timeout_s(level);
        value = read_value(s, spec.key, per_level);
      } else if (top == spec.key) {
        value = read_value(s, spec.key, spec);
      } else {
        auto it = nested.find(top);
        if (it == nested.end()) it = nested.emplace(top, s.section(top)).first;
        value = read_value(it->second, spec.key.substr(top.size() + 1), spec);
      }
      if (d == chosen ||
          std::any_of(chosen->params.begin(), chosen->params.end(),
                      [&](const protocols::ParamSpec& mine) { return mine.key == spec.key; }))
        choice.params.set(spec.key, std::move(value));
    }
  for (auto& [top, section] : nested)
    section.finish();
  // A key of another kind is legal but unused: say so, so that nobody believes `growth`
  // changed an oracle run.
  for (const std::string& top : tops) {
    const auto& declaring = kinds[top];
    if (!s.has(top) ||
        std::find(declaring.begin(), declaring.end(), choice.kind) != declaring.end())
      continue;
    s.warn_at(top, "applies to protocol kind " + listed(declaring) + ", not " + choice.kind +
                       ": it is ignored");
  }
  s.finish();
  return choice;
}

}  // namespace masnet::scenarios
