#include "scenarios/live/live_page.hpp"

#include <string_view>

#include "live_assets.hpp"
#include "scenarios/report/web_assets.hpp"

namespace masnet::live {
namespace {

void replace_once(std::string& text, std::string_view marker, std::string_view content) {
  const std::size_t at = text.find(marker);
  if (at != std::string::npos) text.replace(at, marker.size(), content);
}

}  // namespace

std::string live_page_html() {
  std::string page(kLivePageHtml);
  // Scripts go in last to first, so that no script's text is searched for a marker.
  replace_once(page, "/*LIVE_PAGE_JS*/", kLivePageJs);
  replace_once(page, "/*SCENE_VIEW_JS*/", scenarios::scene_view_js());
  replace_once(page, "/*CHART_JS*/", scenarios::chart_js_source());
  return page;
}

}  // namespace masnet::live
