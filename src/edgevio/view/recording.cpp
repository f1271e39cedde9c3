#include "edgevio/view/recording.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "edgevio/common/base64.h"
#include "edgevio/common/json.h"

namespace edgevio::view {

namespace {

using geometry::SE3;

// Foxglove's schemas as JSON Schema, as much of them as edgevio writes.
const char* const kTime = R"({"type":"object","properties":{"sec":{"type":"integer"},"nsec":{"type":"integer"}}})";
const char* const kVector3 = R"({"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"}}})";
const char* const kQuaternion =
    R"({"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},"z":{"type":"number"},"w":{"type":"number"}}})";

std::string poseSchema() {
  return std::string(R"({"type":"object","properties":{"position":)") + kVector3 + R"(,"orientation":)" + kQuaternion + "}}";
}

std::string frameTransformsSchema() {
  return std::string(R"({"type":"object","properties":{"transforms":{"type":"array","items":{"type":"object","properties":{"timestamp":)") +
         kTime + R"(,"parent_frame_id":{"type":"string"},"child_frame_id":{"type":"string"},"translation":)" + kVector3 +
         R"(,"rotation":)" + kQuaternion + "}}}}}";
}

std::string poseInFrameSchema() {
  return std::string(R"({"type":"object","properties":{"timestamp":)") + kTime + R"(,"frame_id":{"type":"string"},"pose":)" +
         poseSchema() + "}}";
}

std::string posesInFrameSchema() {
  return std::string(R"({"type":"object","properties":{"timestamp":)") + kTime +
         R"(,"frame_id":{"type":"string"},"poses":{"type":"array","items":)" + poseSchema() + "}}}";
}

std::string compressedImageSchema() {
  return std::string(R"({"type":"object","properties":{"timestamp":)") + kTime +
         R"(,"frame_id":{"type":"string"},"data":{"type":"string","contentEncoding":"base64"},"format":{"type":"string"}}})";
}

std::string logSchema() {
  return std::string(R"({"type":"object","properties":{"timestamp":)") + kTime +
         R"(,"level":{"type":"integer"},"message":{"type":"string"},"name":{"type":"string"},"file":{"type":"string"},"line":{"type":"integer"}}})";
}

/// The frames.csv row as an object: one property per column, with its unit and meaning.
std::string frameRecordSchema() {
  std::ostringstream out;
  JsonWriter j(out, false);
  j.beginObject().key("type").value("object").key("properties").beginObject();
  const pipeline::FrameRecord blank;
  for (const pipeline::FrameColumn& c : pipeline::frameColumns()) {
    const pipeline::Cell v = c.value(blank);
    j.key(c.name).beginObject().key("type").value(v.kind == pipeline::Cell::Kind::kText      ? "string"
                                                  : v.kind == pipeline::Cell::Kind::kInteger ? "integer"
                                                                                             : "number");
    j.key("description").value(std::string(c.meaning) + (std::string(c.unit) == "-" ? "" : " [" + std::string(c.unit) + "]"));
    j.endObject();
  }
  j.endObject().endObject();
  return out.str();
}

void time(JsonWriter& j, std::int64_t t_ns) {
  j.beginObject().key("sec").value(static_cast<long long>(t_ns / 1000000000)).key("nsec").value(static_cast<long long>(t_ns % 1000000000)).endObject();
}

void vector3(JsonWriter& j, const Vec3& v) { j.beginObject().key("x").value(v.x()).key("y").value(v.y()).key("z").value(v.z()).endObject(); }

void quaternion(JsonWriter& j, const geometry::SO3& R) {
  const auto& q = R.quaternion();
  j.beginObject().key("x").value(q.x()).key("y").value(q.y()).key("z").value(q.z()).key("w").value(q.w()).endObject();
}

void pose(JsonWriter& j, const SE3& T) {
  j.beginObject().key("position");
  vector3(j, T.translation());
  j.key("orientation");
  quaternion(j, T.so3());
  j.endObject();
}

/// A PosesInFrame of `poses`, thinned evenly to at most `max` (always keeping the newest).
std::string posesInFrame(std::int64_t t_ns, const std::vector<SE3>& poses, std::size_t max) {
  std::ostringstream out;
  JsonWriter j(out, false);
  j.beginObject().key("timestamp");
  time(j, t_ns);
  j.key("frame_id").value("world").key("poses").beginArray();
  const std::size_t stride = std::max<std::size_t>(1, (poses.size() + max - 1) / max);
  for (std::size_t i = (poses.size() - 1) % stride; i < poses.size(); i += stride) pose(j, poses[i]);
  j.endArray().endObject();
  return out.str();
}

/// The ground-truth sample nearest to t_ns, if one is within 20 ms (a 200 Hz ground truth has one within 2.5 ms).
const io::TrajectorySample* nearest(const io::Trajectory& truth, std::int64_t t_ns) {
  constexpr std::int64_t kMaxGapNs = 20000000;
  const auto it = std::lower_bound(truth.begin(), truth.end(), t_ns, [](const io::TrajectorySample& s, std::int64_t t) { return s.t_ns < t; });
  const io::TrajectorySample* best = nullptr;
  for (auto c : {it, it == truth.begin() ? it : it - 1})
    if (c != truth.end() && (!best || std::llabs(c->t_ns - t_ns) < std::llabs(best->t_ns - t_ns))) best = &*c;
  return best && std::llabs(best->t_ns - t_ns) <= kMaxGapNs ? best : nullptr;
}

}  // namespace

Recording::Recording(const std::string& path, const io::Sequence& sequence) : mcap_(path), truth_(sequence.groundTruth()) {
  T_b_c_[0] = sequence.calibration().T_b_c[0];
  T_b_c_[1] = sequence.calibration().T_b_c[1];
  const auto channel = [&](const char* schema, const std::string& definition, const char* topic) {
    return mcap_.addChannel(mcap_.addSchema(schema, "jsonschema", definition), topic, "json");
  };
  tf_ = channel("foxglove.FrameTransforms", frameTransformsSchema(), "/tf");
  pose_ = channel("foxglove.PoseInFrame", poseInFrameSchema(), "/pose");
  const std::uint16_t poses = mcap_.addSchema("foxglove.PosesInFrame", "jsonschema", posesInFrameSchema());
  path_ = mcap_.addChannel(poses, "/path/estimate", "json");
  if (!truth_.empty()) truth_path_ = mcap_.addChannel(poses, "/path/ground_truth", "json");
  keyframes_ = mcap_.addChannel(poses, "/keyframes", "json");
  alignment_ = channel("foxglove.CompressedImage", compressedImageSchema(), "/alignment");
  events_ = channel("foxglove.Log", logSchema(), "/events");
  frame_ = channel("edgevio.FrameRecord", frameRecordSchema(), "/frame");
}

void Recording::writePaths(std::int64_t t_ns) {
  mcap_.write(path_, static_cast<std::uint64_t>(t_ns), posesInFrame(t_ns, estimate_, kMaxPathPoses));
  if (truth_path_) mcap_.write(truth_path_, static_cast<std::uint64_t>(t_ns), posesInFrame(t_ns, truth_so_far_, kMaxPathPoses));
  paths_sent_ns_ = t_ns;
}

void Recording::close() {
  if (last_t_ns_ >= 0 && paths_sent_ns_ != last_t_ns_) writePaths(last_t_ns_);
  mcap_.close();
}

void Recording::log(std::int64_t t_ns, int level, const std::string& message) {
  std::ostringstream out;
  JsonWriter j(out, false);
  j.beginObject().key("timestamp");
  time(j, t_ns);
  j.key("level").value(level).key("message").value(message).key("name").value("edgevio").key("file").value("").key("line").value(0).endObject();
  mcap_.write(events_, static_cast<std::uint64_t>(t_ns), out.str());
}

void Recording::write(const pipeline::FrameRecord& r, const std::vector<std::uint8_t>& jpeg) {
  const auto t = static_cast<std::uint64_t>(r.t_ns);
  {
    std::ostringstream out;
    JsonWriter j(out, false);
    j.beginObject().key("transforms").beginArray();
    const auto transform = [&](const char* parent, const char* child, const SE3& T) {
      j.beginObject().key("timestamp");
      time(j, r.t_ns);
      j.key("parent_frame_id").value(parent).key("child_frame_id").value(child).key("translation");
      vector3(j, T.translation());
      j.key("rotation");
      quaternion(j, T.so3());
      j.endObject();
    };
    transform("world", "body", r.T_w_b);
    transform("body", "cam0", T_b_c_[0]);
    transform("body", "cam1", T_b_c_[1]);
    j.endArray().endObject();
    mcap_.write(tf_, t, out.str());
  }
  {
    std::ostringstream out;
    JsonWriter j(out, false);
    j.beginObject().key("timestamp");
    time(j, r.t_ns);
    j.key("frame_id").value("world").key("pose");
    pose(j, r.T_w_b);
    j.endObject();
    mcap_.write(pose_, t, out.str());
  }
  estimate_.push_back(r.T_w_b);
  if (truth_path_) {
    if (const io::TrajectorySample* g = nearest(truth_, r.t_ns)) {
      if (!truth_placed_) {
        T_est_gt_ = r.T_w_b * g->T_w_b.inverse();
        truth_placed_ = true;
      }
      truth_so_far_.push_back(T_est_gt_ * g->T_w_b);
    }
  }
  last_t_ns_ = r.t_ns;
  if (paths_sent_ns_ < 0 || r.t_ns - paths_sent_ns_ >= kPathPeriodNs) writePaths(r.t_ns);
  if (r.isKeyframe()) {
    keyframe_poses_.push_back(r.T_w_b);
    mcap_.write(keyframes_, t, posesInFrame(r.t_ns, keyframe_poses_, kMaxPathPoses));
  }
  if (!jpeg.empty()) {
    std::ostringstream out;
    JsonWriter j(out, false);
    j.beginObject().key("timestamp");
    time(j, r.t_ns);
    j.key("frame_id").value("cam0").key("data").value(base64(jpeg.data(), jpeg.size())).key("format").value("jpeg").endObject();
    mcap_.write(alignment_, t, out.str());
  }
  // Foxglove's log levels: 2 info, 3 warning, 4 error.
  if (r.isKeyframe()) log(r.t_ns, 2, std::string("keyframe: ") + options::nameOf(tracking::kKeyframeReasonChoices, r.keyframe));
  if (r.aligned && !r.selfCheckPassed()) log(r.t_ns, 3, "the alignment failed its self check");
  if (r.external_check == pipeline::ExternalCheck::kRejected) log(r.t_ns, 3, "the external check rejected the tracking link");
  if (r.loop_links > 0) log(r.t_ns, 2, std::to_string(r.loop_links) + " loop closure(s)");
  if (r.lost_since_ns >= 0) log(r.t_ns, 4, "lost: " + r.lost_reason);
  for (const std::string& e : r.events) log(r.t_ns, 3, e);
  {
    std::ostringstream out;
    JsonWriter j(out, false);
    j.beginObject();
    const std::vector<std::string> cells = pipeline::frameCells(r);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const pipeline::FrameColumn& c = pipeline::frameColumns()[i];
      j.key(c.name);
      const pipeline::Cell v = c.value(r);
      if (v.kind == pipeline::Cell::Kind::kText) j.value(cells[i]);
      else if (v.kind == pipeline::Cell::Kind::kInteger) j.value(v.integer);
      else j.value(v.real);
    }
    j.endObject();
    mcap_.write(frame_, t, out.str());
  }
}

}  // namespace edgevio::view
