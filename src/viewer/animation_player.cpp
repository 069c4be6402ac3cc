#include <tessera/viewer/animation_player.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include <tessera/scene/animation.h>

namespace tessera::viewer {

void prepareClip(LoadedScene& loaded, int index) {
  loaded.clip = -1;
  if (index < 0 || static_cast<size_t>(index) >= loaded.graph.animations.size()) {
    loaded.bounds = loaded.scene.bounds();
    return;
  }
  loaded.clip = index;
  // clipBounds leaves the graph posed at the clip's start: the scene follows it, and the bounds
  // are those of that pose (not of whatever pose the scene had) and of every later one.
  const Bounds moving =
      clipBounds(loaded.graph.animations[static_cast<size_t>(index)], loaded.graph);
  updateInstances(loaded.graph, 0, loaded.scene);
  loaded.bounds = loaded.scene.bounds();
  if (!moving.empty()) {
    loaded.bounds.add(moving.min);
    loaded.bounds.add(moving.max);
  }
}

void AnimationPlayer::reset(SceneGraph graph, int clip) {
  graph_ = std::move(graph);
  clip_ = clip >= 0 && static_cast<size_t>(clip) < graph_.animations.size() ? clip : -1;
  playing_ = false;
  time_ = 0.0;
}

bool AnimationPlayer::togglePlaying(Clock::time_point now) {
  if (!hasClip()) return false;
  playing_ = !playing_;
  last_update_ = now;  // the time paused does not count
  return true;
}

bool AnimationPlayer::update(Clock::time_point now, Scene& scene) {
  if (!playing_ || !hasClip()) return false;
  const double elapsed = std::chrono::duration<double>(now - last_update_).count();
  last_update_ = now;
  const double duration = graph_.animations[static_cast<size_t>(clip_)].duration();
  if (!(duration > 0.0) || !(elapsed > 0.0)) return false;
  time_ = std::fmod(time_ + elapsed, duration);
  pose(scene);
  return true;
}

void AnimationPlayer::pose(Scene& scene) {
  const Animation& clip = graph_.animations[static_cast<size_t>(clip_)];
  clip.apply(clip.startTime() + static_cast<float>(time_), graph_);
  graph_.updateWorld();
  updateInstances(graph_, 0, scene);
}

std::string AnimationPlayer::describe() const {
  if (!hasClip()) return "";
  const Animation& clip = graph_.animations[static_cast<size_t>(clip_)];
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on "#" + std::to_string(...).
  std::string line = "animation ";
  if (clip.name.empty())
    line.append("#").append(std::to_string(clip_));
  else
    line.append("'").append(clip.name).append("'");
  char times[64];
  std::snprintf(times, sizeof times, " %.2f / %.2f s, ", time_,
                static_cast<double>(clip.duration()));
  return line.append(times).append(playing_ ? "playing" : "paused");
}

std::string AnimationPlayer::state() const {
  char time[32];
  std::snprintf(time, sizeof time, "%.3f s", time_);
  return std::string("animation ") + (playing_ ? "playing from " : "paused at ") + time;
}

}  // namespace tessera::viewer
