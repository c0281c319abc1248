#include "protocols/protocol_listing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace masnet::protocols {

namespace {

std::string type_name(ParamType type) {
  switch (type) {
    case ParamType::real:
      return "number";
    case ParamType::integer:
      return "integer";
    case ParamType::boolean:
      return "bool";
    case ParamType::choice:
      return "choice";
  }
  return "?";
}

// The allowed values as the scenario reference writes them: "> 0", "`a`, `b`".
std::string allowed_markdown(const ParamSpec& spec) {
  if (spec.type == ParamType::boolean) return "—";
  if (spec.type != ParamType::choice) return spec.allowed_text();
  std::string out;
  for (const std::string& c : spec.choices)
    out += (out.empty() ? "`" : ", `") + c + "`";
  return out;
}

std::string default_markdown(const ParamSpec& spec) {
  return spec.type == ParamType::choice ? "`" + spec.default_text() + "`" : spec.default_text();
}

std::string or_dash(const std::string& text) {
  return text.empty() ? "—" : text;
}

}  // namespace

std::string protocol_listing_text() {
  std::string out;
  for (const ProtocolDefinition* d : registered_protocols()) {
    out += fmt::format("{} — {}\n", d->name, d->summary);
    for (const ParamSpec& p : d->params)
      out += fmt::format("  {:<16} {:<8} default {:<10} allowed {:<20} {:<12} {}\n", p.key,
                         type_name(p.type), p.default_text(), p.allowed_text(),
                         p.unit.empty() ? "" : "(" + p.unit + ")", p.meaning);
  }
  return out;
}

std::string protocol_table_markdown() {
  return protocol_table_markdown(registered_protocols());
}

std::string protocol_table_markdown(const std::vector<const ProtocolDefinition*>& all) {
  std::string kinds;
  for (const ProtocolDefinition* d : all)
    kinds += (kinds.empty() ? "`" : ", `") + d->name + "`";
  std::string out =
      "| key | type | default | allowed | unit | kind | meaning |\n"
      "|---|---|---|---|---|---|---|\n";
  out += fmt::format(
      "| `kind` | choice | `{}` | {} | — | — | the protocol; `masnet protocols` "
      "lists each with its keys |\n",
      kDefaultProtocol, kinds);
  std::vector<std::string> done;
  for (const ProtocolDefinition* d : all)
    for (const ParamSpec& p : d->params) {
      if (std::find(done.begin(), done.end(), p.key) != done.end()) continue;
      done.push_back(p.key);
      std::string declared_by;
      for (const ProtocolDefinition* other : all)
        for (const ParamSpec& q : other->params)
          if (q.key == p.key) declared_by += (declared_by.empty() ? "" : ", ") + other->name;
      out += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", p.key, type_name(p.type),
                         default_markdown(p), allowed_markdown(p), or_dash(p.unit), declared_by,
                         p.meaning);
    }
  return out;
}

}  // namespace masnet::protocols
