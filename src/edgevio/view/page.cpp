#include "edgevio/view/page.h"

#include <cstddef>
#include <stdexcept>

#include "edgevio/common/base64.h"

namespace edgevio::view {

namespace embedded {
extern const unsigned char kThreeJs[];
extern const std::size_t kThreeJsSize;
extern const unsigned char kViewerHtml[];
extern const std::size_t kViewerHtmlSize;
}  // namespace embedded

namespace {

void replaceOnce(std::string* text, const std::string& placeholder, const std::string& value) {
  const std::size_t at = text->find(placeholder);
  if (at == std::string::npos) throw std::logic_error("viewer.html lacks " + placeholder);
  text->replace(at, placeholder.size(), value);
}

}  // namespace

std::string scriptSafe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) text.replace(at, 2, "<\\/");
  return text;
}

std::string viewerPage(const std::string& run_json) {
  std::string page(reinterpret_cast<const char*>(embedded::kViewerHtml), embedded::kViewerHtmlSize);
  // An import map may name a data: URL: the module needs no server and no
  // network, and file:// pages can import it.
  replaceOnce(&page, "@EDGEVIO_THREE_URL@", "data:text/javascript;base64," + base64(embedded::kThreeJs, embedded::kThreeJsSize));
  replaceOnce(&page, "@EDGEVIO_RUN_DATA@", scriptSafe(run_json));
  return page;
}

}  // namespace edgevio::view
