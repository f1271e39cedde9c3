#include "edgevio/eval/report.h"

#include <ostream>

#include "edgevio/common/format.h"
#include "edgevio/common/json.h"

namespace edgevio::eval {

void writeJson(std::ostream& out, const EvalResult& r) {
  JsonWriter j(out);
  j.beginObject();
  j.key("matched").value(r.matched);
  j.key("align").value(alignmentName(r.alignment));
  if (r.alignment == AlignmentKind::kSim3) j.key("scale").value(r.transform.scale);
  j.key("ate_rmse_m").value(r.ate_rmse_m);
  j.key("ate_mean_m").value(r.ate_mean_m);
  j.key("ate_median_m").value(r.ate_median_m);
  j.key("ate_max_m").value(r.ate_max_m);
  j.key("rpe").beginArray();
  for (const auto& e : r.rpe) {
    j.beginObject();
    j.key("delta_m").value(e.delta_m);
    j.key("pairs").value(e.pairs);
    j.key("trans_rmse_m").value(e.trans_rmse_m);
    j.key("rot_rmse_deg").value(e.rot_rmse_deg);
    j.endObject();
  }
  j.endArray();
  j.key("are_rot_deg_per_m").value(r.are_rot_deg_per_m);
  j.key("are_trans_m_per_m").value(r.are_trans_m_per_m);
  j.key("are_segments").value(r.are_segments);
  j.key("are_lengths_m").beginArray();
  for (double l : r.are_lengths_m) j.value(l);
  j.endArray();
  j.key("length_m").value(r.length_m);
  j.key("duration_s").value(r.duration_s);
  j.endObject();
}

void writeTable(std::ostream& out, const EvalResult& r) {
  const auto row = [&](const std::string& name, double v, const char* unit) {
    out << formatText("  %-34s %12.6f %s\n", name.c_str(), v, unit);
  };
  out << "Trajectory evaluation (" << r.matched << " matched poses, " << alignmentName(r.alignment)
      << " alignment)\n";
  row("length", r.length_m, "m");
  row("duration", r.duration_s, "s");
  if (r.alignment == AlignmentKind::kSim3) row("scale (est -> gt)", r.transform.scale, "");
  row("ATE RMSE", r.ate_rmse_m, "m");
  row("ATE mean", r.ate_mean_m, "m");
  row("ATE median", r.ate_median_m, "m");
  row("ATE max", r.ate_max_m, "m");
  for (const auto& e : r.rpe) {
    row(formatText("RPE trans RMSE, %g m (%zu pairs)", e.delta_m, e.pairs), e.trans_rmse_m, "m");
    row(formatText("RPE rot RMSE, %g m", e.delta_m), e.rot_rmse_deg, "deg");
  }
  row(formatText("ARE rot (%zu segments)", r.are_segments), r.are_rot_deg_per_m, "deg/m");
  row("ARE trans", r.are_trans_m_per_m, "m/m");
}

}  // namespace edgevio::eval
