#pragma once
// The live viewer's page: one HTML document with every script inlined (Chart.js, the scene
// drawing shared with the report's replay, the page's own), so it works without a network.
#include <string>

namespace masnet::live {

/// Throws std::runtime_error when Chart.js cannot be found (as the report does).
std::string live_page_html();

}  // namespace masnet::live
