// libFuzzer target for the scenario loader and its --set parser (docs/testing.md). Besides the
// sanitizers' own checks (memory errors, undefined behaviour, leaks, 1 GiB allocations, hangs),
// every result must keep the loader's promise to the user: bad input yields at least one
// diagnostic, each located as "file:line:col" or "--set a.b=v", each message printable and short.
// A broken promise traps, so libFuzzer saves the input as a crash.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "scenarios/loader/scenario.hpp"

// The checks that need the loader's capped and escaped messages; OFF keeps the others only.
#ifndef MASNET_FUZZ_STRICT_MESSAGES
#define MASNET_FUZZ_STRICT_MESSAGES 1
#endif

namespace {

constexpr std::size_t kMaxMessageBytes = 2000;

// Relative sensor files ("sensors_bad_line.csv") resolve next to this name, so the seeds from
// tests/scenarios/malformed reach the CSV reader too.
const std::string kFileName = MASNET_FUZZ_SCENARIO_DIR "/fuzz-input.yaml";

// At most 300 bytes of `text`, control bytes and bytes from 0x7f up as \xHH: the text itself
// may be what is wrong.
std::string shown(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < 300; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (text.size() > 300) out += "...";
  return out;
}

[[noreturn]] void fail(const char* property, const masnet::scenarios::Diagnostic* d) {
  std::fprintf(stderr, "fuzz_scenario_loader: broken property: %s\n", property);
  if (d) {
    std::fprintf(stderr, "  location (%zu bytes): %s\n  message (%zu bytes): %s\n",
                 d->location.size(), shown(d->location).c_str(), d->message.size(),
                 shown(d->message).c_str());
  }
  __builtin_trap();
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

// "FILE:LINE:COL" with a non-empty FILE (which may itself hold colons) and positive numbers.
bool is_file_line_col(std::string_view location) {
  const std::size_t col_colon = location.rfind(':');
  if (col_colon == std::string_view::npos || col_colon == 0) return false;
  const std::size_t line_colon = location.rfind(':', col_colon - 1);
  if (line_colon == std::string_view::npos || line_colon == 0) return false;
  const std::string_view line = location.substr(line_colon + 1, col_colon - line_colon - 1);
  const std::string_view column = location.substr(col_colon + 1);
  return all_digits(line) && all_digits(column) && line.find_first_not_of('0') != line.npos &&
         column.find_first_not_of('0') != column.npos;
}

// No raw control byte (C0 or DEL): a message must not move the user's cursor or hide text.
// Bytes from 0x80 up are left alone (UTF-8 in names and paths).
bool is_printable(std::string_view text) {
  for (unsigned char c : text)
    if (c < 0x20 || c == 0x7f) return false;
  return true;
}

void check_result(const masnet::scenarios::LoadResult& result) {
  if (!result.scenario && result.diagnostics.empty())
    fail("no scenario and no diagnostic (a missing diagnostic)", nullptr);
  if (result.scenario && !result.diagnostics.empty())
    fail("a scenario together with diagnostics", &result.diagnostics.front());
  for (const masnet::scenarios::Diagnostic& d : result.diagnostics) {
    if (d.location.empty()) fail("empty location", &d);
    if (d.location.rfind("--set ", 0) != 0 && !is_file_line_col(d.location))
      fail("location is neither FILE:LINE:COL nor '--set ...'", &d);
    if (d.message.empty()) fail("empty message", &d);
#if MASNET_FUZZ_STRICT_MESSAGES
    if (d.message.size() > kMaxMessageBytes) fail("message longer than 2000 bytes", &d);
    if (!is_printable(d.message)) fail("control byte in message", &d);
    if (!is_printable(d.location)) fail("control byte in location", &d);
#endif
  }
#if MASNET_FUZZ_STRICT_MESSAGES
  // summary.json and the run's fingerprint dump the resolved scenario; text the user gave (a
  // name, a sensor file) must not make that throw (nlohmann::json refuses invalid UTF-8).
  if (result.scenario) {
    try {
      (void)result.scenario->resolved.dump();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "  %s\n", e.what());
      fail("the resolved scenario cannot be written as JSON", nullptr);
    }
  }
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const masnet::fuzz::FuzzInput input =
      masnet::fuzz::split_fuzz_input({reinterpret_cast<const char*>(data), size});
  masnet::scenarios::LoadResult result;
  // As `masnet validate` loads: sensors counted, not built (a 10^7 grid is legal but takes
  // seconds under the sanitizers), and no input may raise the limits (limits.allow_huge).
  masnet::scenarios::LoadOptions options;
  options.build_sensors = false;
  options.allow_huge = false;
  try {
    result = masnet::scenarios::load_scenario_text(input.yaml_text, kFileName, input.overrides,
                                                   std::nullopt, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "  %s\n", e.what());
    fail("load_scenario_text threw (it promises diagnostics instead)", nullptr);
  } catch (...) {
    fail("load_scenario_text threw a non-standard exception", nullptr);
  }
  check_result(result);
  return 0;
}
