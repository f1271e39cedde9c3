#include "edgevio/pipeline/keyframe_store.h"

namespace edgevio::pipeline {

void KeyframeStore::add(std::shared_ptr<const tracking::KeyframeData> data, const geometry::SE3& T_w_b, bool in_window) {
  // A keyframe outside the window served only as the current one.
  for (auto it = keyframes_.begin(); it != keyframes_.end();) it = it->second.in_window ? std::next(it) : keyframes_.erase(it);
  const std::int64_t t = data->t_ns;
  keyframes_[t] = Keyframe{std::move(data), T_w_b, in_window};
}

void KeyframeStore::setData(std::shared_ptr<const tracking::KeyframeData> data) {
  if (const auto it = keyframes_.find(data->t_ns); it != keyframes_.end()) it->second.data = std::move(data);
}

const Keyframe* KeyframeStore::current() const { return keyframes_.empty() ? nullptr : &keyframes_.rbegin()->second; }

std::optional<std::int64_t> KeyframeStore::currentTime() const {
  if (keyframes_.empty()) return std::nullopt;
  return keyframes_.rbegin()->first;
}

bool KeyframeStore::isKeyframe(std::int64_t t_ns) const {
  const auto it = keyframes_.find(t_ns);
  return it != keyframes_.end() && it->second.in_window;
}

void KeyframeStore::leftWindow(std::int64_t t_ns) {
  const auto it = keyframes_.find(t_ns);
  if (it == keyframes_.end()) return;
  if (t_ns != currentTime()) {
    keyframes_.erase(it);
  } else {
    it->second.in_window = false;
  }
}

void KeyframeStore::windowRestarted() {
  if (keyframes_.empty()) return;
  Keyframe current = std::move(keyframes_.rbegin()->second);
  const std::int64_t t = keyframes_.rbegin()->first;
  keyframes_.clear();
  current.in_window = false;
  keyframes_.emplace(t, std::move(current));
}

void KeyframeStore::enterWindow(std::int64_t t_ns) {
  if (const auto it = keyframes_.find(t_ns); it != keyframes_.end()) it->second.in_window = true;
}

}  // namespace edgevio::pipeline
