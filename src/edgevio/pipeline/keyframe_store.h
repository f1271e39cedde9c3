#pragma once
// The keyframes (METHOD.md §3): the one place they live. Keyed by time, each
// holds its images as alignment needs them, the body pose it was made at,
// and whether its state is still in the estimator's window. The newest is
// the current keyframe, which frames are tracked against. A keyframe that
// leaves the window keeps nothing but its time, unless it is the current one.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>

#include "edgevio/geometry/se3.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

struct Keyframe {
  std::shared_ptr<const tracking::KeyframeData> data;
  geometry::SE3 T_w_b;     ///< the body pose it was made at (the window's estimate supersedes it while it is in the window)
  bool in_window = false;  ///< its state is in the estimator's window
};

class KeyframeStore {
 public:
  /// Adds the newest keyframe, which becomes the current one. Its data may
  /// hold only its time at first (the rest made later: setData).
  void add(std::shared_ptr<const tracking::KeyframeData> data, const geometry::SE3& T_w_b, bool in_window);
  /// The whole data of the keyframe at data->t_ns, if it is still kept.
  void setData(std::shared_ptr<const tracking::KeyframeData> data);

  /// The keyframe frames are tracked against; null before the first.
  const Keyframe* current() const;
  std::optional<std::int64_t> currentTime() const;
  /// Whether the window's state at t_ns is a keyframe.
  bool isKeyframe(std::int64_t t_ns) const;

  /// The state at t_ns left the window; its keyframe (if it is one) is
  /// dropped unless it is the current one.
  void leftWindow(std::int64_t t_ns);
  /// The window restarted: every keyframe has left it; all but the current one are dropped.
  void windowRestarted();
  /// The window restarted at the current keyframe's state (t_ns): it is in the window.
  void enterWindow(std::int64_t t_ns);

  /// The keyframes in the window, oldest first.
  template <class F>
  void forEachInWindow(F&& f) const {
    for (const auto& [t, k] : keyframes_)
      if (k.in_window) f(k);
  }

 private:
  std::map<std::int64_t, Keyframe> keyframes_;
};

}  // namespace edgevio::pipeline
