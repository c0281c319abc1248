#pragma once
// Opening a written HTML page in headless Chromium, for the report tests: the DOM after its
// scripts ran, Chromium's console log, and optionally a screenshot.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "text_files.hpp"

namespace masnet::test {

/// Under CI (the variable CI set, as CI's runner does), where setup installs Chromium and
/// Chart.js, a missing one is a failure; elsewhere the test is skipped with a visible warning.
inline bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci && *ci && std::string(ci) != "false" && std::string(ci) != "0";
}

// Skips the current test (visibly) unless `present`; fails it instead under CI.
#define MASNET_REQUIRE_TOOL(present, what)                                                       \
  do {                                                                                           \
    if (!(present)) {                                                                            \
      if (::masnet::test::in_ci()) FAIL(std::string(what) + " is missing, and CI must have it"); \
      WARN(std::string("skipped: ") + (what) + " is missing");                                   \
      return;                                                                                    \
    }                                                                                            \
  } while (false)

inline const std::filesystem::path kChromium = "/usr/bin/chromium";

struct HeadlessPage {
  int status = -1;  // of the shell running Chromium (0: it exited normally)
  std::string dom, log;
};

/// Loads `page` in headless Chromium with a fresh profile under `work_dir`, which also receives
/// dom.html and chromium.log (and the screenshot when `screenshot` is not empty).
inline HeadlessPage open_headless(const std::filesystem::path& page,
                                  const std::filesystem::path& work_dir,
                                  const std::filesystem::path& screenshot = {}) {
  const std::filesystem::path dom = work_dir / "dom.html", log = work_dir / "chromium.log";
  const std::string shot =
      screenshot.empty()
          ? std::string()
          : fmt::format("--window-size=1200,2000 --screenshot='{}' ", screenshot.string());
  const std::string command = fmt::format(
      "timeout 120 '{}' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--user-data-dir='{}' --enable-logging=stderr --v=0 {}--dump-dom 'file://{}' > '{}' 2> '{}'",
      kChromium.string(), (work_dir / "chromium-profile").string(), shot,
      std::filesystem::absolute(page).string(), dom.string(), log.string());
  HeadlessPage out;
  out.status = std::system(command.c_str());
  out.dom = slurp(dom);
  out.log = slurp(log);
  return out;
}

}  // namespace masnet::test
