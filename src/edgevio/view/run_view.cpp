#include "edgevio/view/run_view.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "edgevio/common/base64.h"
#include "edgevio/common/error.h"
#include "edgevio/common/json.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/common/time.h"
#include "edgevio/common/yaml_file.h"
#include "edgevio/eval/batch.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/pipeline/component_times.h"
#include "edgevio/view/page.h"

namespace edgevio::view {

namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writePoint(JsonWriter& j, double t_s, const Vec3& p) {
  j.beginArray().value(t_s).value(p.x()).value(p.y()).value(p.z()).endArray();
}

}  // namespace

std::string runViewJson(const std::string& run_dir, const eval::EvalOptions& options, std::vector<std::string>* notes) {
  const fs::path run(run_dir);
  const fs::path frames_csv = run / "frames.csv";
  if (!fs::exists(frames_csv)) throw InputError(run_dir, 0, "not a run folder: no frames.csv (write one with edgevio run --out)");
  const fs::path summary_json = run / "summary.json";
  std::string summary = "{}";
  if (fs::exists(summary_json)) {
    // Goes into the page as it is: a file cut short (a run killed while
    // writing it) is an error naming its line here, not a blank page.
    loadYamlFile(summary_json.string());
    summary = readBytes(summary_json);
  } else {
    notes->push_back("no summary.json: the run did not finish");
  }

  std::ostringstream out;
  JsonWriter j(out, false);
  j.beginObject().key("live").value(false);
  TableReader in(frames_csv.string(), TableReader::Separator::kComma, TableReader::Header::kColumnNames);
  j.key("columns").beginArray();
  for (const std::string& c : in.columns()) j.value(c);
  j.endArray().key("frames").beginArray();
  const std::size_t t_column = in.column("timestamp_ns");
  std::vector<std::string> times;
  while (in.next()) {
    j.beginArray();
    for (std::size_t i = 0; i < in.size(); ++i) j.value(in.field(i));
    j.endArray();
    times.push_back(in.field(t_column));
  }
  j.endArray();

  // The estimate in the ground truth's frame when there is one, else as it was estimated.
  const eval::RunEvaluation e = eval::evaluateRunFolder(run_dir, options);
  j.key("estimate").beginArray();
  std::vector<std::pair<std::int64_t, Vec3>> positions;
  if (e.ok) {
    for (std::size_t i = 0; i < e.result.t_ns.size(); ++i) positions.emplace_back(e.result.t_ns[i], e.result.est_positions_aligned[i]);
  } else {
    notes->push_back("no ATE: " + e.failure);
    if (fs::exists(run / "trajectory_tum.txt"))
      for (const io::TrajectorySample& s : io::readTrajectory((run / "trajectory_tum.txt").string()))
        positions.emplace_back(s.t_ns, s.T_w_b.translation());
  }
  const std::int64_t t0 = positions.empty() ? 0 : positions.front().first;
  for (const auto& [t, p] : positions) writePoint(j, toSeconds(t - t0), p);
  j.endArray().key("truth").beginArray();
  if (e.ok)
    for (std::size_t i = 0; i < e.result.t_ns.size(); ++i) writePoint(j, toSeconds(e.result.t_ns[i] - t0), e.result.gt_positions[i]);
  j.endArray().key("positions").beginObject();
  for (const auto& [t, p] : positions) j.key(std::to_string(t)).beginArray().value(p.x()).value(p.y()).value(p.z()).endArray();
  j.endObject().key("ate");
  if (e.ok) {
    j.beginObject().key("rmse_m").value(e.result.ate_rmse_m).key("alignment").value(eval::alignmentName(e.result.alignment));
    j.key("errors").beginArray();
    for (std::size_t i = 0; i < e.result.t_ns.size(); ++i)
      j.beginArray().value(toSeconds(e.result.t_ns[i] - t0)).value(e.result.ate_errors_m[i]).endArray();
    j.endArray().endObject();
  } else {
    j.null();
  }

  j.key("timing").beginArray();
  for (const pipeline::ComponentTime& c : pipeline::readComponentTimes(frames_csv.string()))
    j.beginObject().key("component").value(c.component).key("per").value(c.per).key("mean_ms").value(c.mean_ms)
        .key("median_ms").value(c.median_ms).key("p90_ms").value(c.p90_ms).key("count").value(c.count).endObject();
  j.endArray();

  j.key("pictures").beginObject();
  for (const std::string& t : times) {
    const fs::path picture = run / "alignment" / (t + ".jpg");
    if (!fs::exists(picture)) continue;
    const std::string jpeg = readBytes(picture);
    j.key(t).value("data:image/jpeg;base64," + base64(reinterpret_cast<const std::uint8_t*>(jpeg.data()), jpeg.size()));
  }
  j.endObject().endObject();
  // summary.json is the run's own JSON: it goes in as it is.
  std::string json = out.str();
  return "{\"summary\":" + summary + "," + json.substr(1);
}

void writeRunView(const std::string& run_dir, const std::string& out_file, const eval::EvalOptions& options,
                  std::vector<std::string>* notes) {
  const std::string page = viewerPage(runViewJson(run_dir, options, notes));
  std::ofstream f(out_file, std::ios::binary);
  f << page;
  f.close();
  if (!f) throw InputError(out_file, 0, "cannot write the page");
}

}  // namespace edgevio::view
