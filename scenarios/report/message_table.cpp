#include "scenarios/report/message_table.hpp"

#include <cmath>

#include <fmt/format.h>

#include "scenarios/report/report.hpp"

namespace masnet::scenarios {
using nlohmann::json;

namespace {

std::string format_count(double v) {
  return fmt::format("{:.0f}", v);
}

// The contended levels' keys under each type and the total, with their column titles.
struct ContentionColumn {
  const char* key;
  const char* title;
  bool seconds;
};
constexpr ContentionColumn kContentionColumns[] = {{"delivered", "delivered", false},
                                                   {"collided", "collided", false},
                                                   {"channel_lost", "lost to the channel", false},
                                                   {"dropped", "dropped", false},
                                                   {"retries", "retries", false},
                                                   {"backoffs", "backoffs", false},
                                                   {"latency_mean_s", "mean latency (s)", true},
                                                   {"latency_p99_s", "p99 latency (s)", true}};

bool has_contention(const json& messages) {
  return messages.contains("total") && messages["total"].contains("collided");
}

// One row's contention cells; `cell_tag` is td or th.
std::string contention_cells(const json& v, const char* cell_tag) {
  std::string out;
  for (const ContentionColumn& c : kContentionColumns) {
    const json value = v.value(c.key, json());
    std::string text = "—";
    if (value.is_number())
      text = c.seconds ? fmt::format("{:.4g}", value.get<double>())
                       : format_count(value.get<double>());
    out += fmt::format("<{0} class=\"num\">{1}</{0}>", cell_tag, text);
  }
  return out;
}

}  // namespace

std::string messages_table(const json& summary) {
  if (!summary.contains("messages")) return "<p>No message statistics.</p>\n";
  const json& m = summary["messages"];
  const json by_type = m.value("by_type", json::object());
  const double total = m.contains("total") ? m["total"].value("count", 0.0) : 0.0;
  const bool contended = has_contention(m);
  std::string out =
      "<table id=\"messages-by-type\"><thead><tr><th>type</th><th class=\"num\">sent</th><th "
      "class=\"num\">bytes "
      "sent</th><th class=\"num\">share of sent</th><th class=\"num\">receptions</th><th "
      "class=\"num\">bytes "
      "received</th>";
  if (contended)
    for (const ContentionColumn& c : kContentionColumns)
      out += fmt::format("<th class=\"num\">{}</th>", c.title);
  out += "</tr></thead><tbody>\n";
  for (const auto& [type, v] : by_type.items()) {
    const double count = v.value("count", 0.0);
    out += fmt::format(
        "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{:.1f} "
        "%</td>"
        "<td class=\"num\">{}</td><td class=\"num\">{}</td>{}</tr>\n",
        escape_html(type), format_count(count), format_count(v.value("bytes", 0.0)),
        total > 0 ? 100.0 * count / total : 0.0, format_count(v.value("rx_count", 0.0)),
        format_count(v.value("rx_bytes", 0.0)), contended ? contention_cells(v, "td") : "");
  }
  if (m.contains("total"))
    out += fmt::format(
        "<tr><th>total</th><th class=\"num\">{}</th><th class=\"num\">{}</th><th class=\"num\">100 "
        "%</th>"
        "<th></th><th></th>{}</tr>\n",
        format_count(m["total"].value("count", 0.0)), format_count(m["total"].value("bytes", 0.0)),
        contended ? contention_cells(m["total"], "th") : "");
  return out + "</tbody></table>\n";
}

}  // namespace masnet::scenarios
