#pragma once
// The viewer's page (viewer.html beside this file, compiled into the
// program): one self-contained HTML file with three.js inside it, for a
// finished run (`edgevio view`) or a live one (`edgevio run --view`).
#include <string>

namespace edgevio::view {

/// The page with `run_json` as its run data. `run_json` is one JSON object:
/// summary, columns, frames (frames.csv rows as strings), estimate and truth
/// ([t_s, x, y, z] each), positions (t_ns → [x, y, z]), ate ({rmse_m,
/// alignment, errors: [t_s, m]}, or null), timing, pictures (t_ns → data:
/// URL) and live (true: the page reads /events).
std::string viewerPage(const std::string& run_json);

/// `text` made safe inside an HTML <script> element (no "</" closes it early).
std::string scriptSafe(std::string text);

}  // namespace edgevio::view
