#include "edgevio/view/live_view.h"

#include <sstream>

#include "edgevio/common/base64.h"
#include "edgevio/common/json.h"
#include "edgevio/view/page.h"

namespace edgevio::view {

namespace {

std::string emptyRun(const std::string& mode, const std::string& sequence) {
  std::ostringstream out;
  JsonWriter j(out, false);
  j.beginObject().key("summary").beginObject().key("mode").value(mode).key("sequence").value(sequence).endObject();
  j.key("live").value(true).key("columns").beginArray();
  for (const pipeline::FrameColumn& c : pipeline::frameColumns()) j.value(c.name);
  j.endArray();
  for (const char* list : {"frames", "estimate", "truth", "timing"}) j.key(list).beginArray().endArray();
  for (const char* map : {"positions", "pictures"}) j.key(map).beginObject().endObject();
  j.key("ate").null().endObject();
  return out.str();
}

}  // namespace

LiveView::LiveView(int port, const std::string& mode, const std::string& sequence)
    : server_(port, viewerPage(emptyRun(mode, sequence))) {}

void LiveView::frame(const pipeline::FrameRecord& r, const std::vector<std::uint8_t>& jpeg) {
  const auto event = [&](bool with_picture) {
    std::ostringstream out;
    JsonWriter j(out, false);
    j.beginObject().key("row").beginArray();
    for (const std::string& cell : pipeline::frameCells(r)) j.value(cell);
    j.endArray().key("position").beginArray();
    for (int i = 0; i < 3; ++i) j.value(r.T_w_b.translation()[i]);
    j.endArray();
    if (with_picture && !jpeg.empty()) j.key("picture").value("data:image/jpeg;base64," + base64(jpeg.data(), jpeg.size()));
    j.endObject();
    return out.str();
  };
  const std::string full = event(true);
  server_.publish(full, jpeg.empty() ? full : event(false));
}

void LiveView::finish(const pipeline::RunSummary& summary) {
  std::ostringstream s;
  pipeline::writeSummaryJson(s, summary);
  const std::string event = "{\"summary\": " + s.str() + "}";
  server_.publish(event, event);
  server_.finish();
}

}  // namespace edgevio::view
