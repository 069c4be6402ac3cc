// The viewer's animation playback (the space bar): one clip of the loaded scene graph, played by
// wall-clock time and looping over the clip's span, or paused on the pose it reached. Each pose
// is render's: clip.apply(t, graph), graph.updateWorld(), updateInstances(graph, 0, scene). No
// SDL: the caller passes the time.
#pragma once

#include <chrono>
#include <string>

#include <tessera/scene/graph.h>
#include <tessera/scene/scene.h>
#include <tessera/viewer/scene_loader.h>

namespace tessera::viewer {

// Picks clip `index` of the loaded graph (-1: none; the caller checks the index), poses the scene
// at the clip's start and sets `loaded.bounds` to the scene's bounds with every pose of the clip
// (clipBounds), so that the framing camera and its near and far planes hold the whole motion.
void prepareClip(LoadedScene& loaded, int index);

class AnimationPlayer {
 public:
  using Clock = std::chrono::steady_clock;

  // The clip `clip` of `graph` (none when -1), paused at its start; the scene's instances are the
  // graph's from object 0 (makeModelScene's order).
  void reset(SceneGraph graph, int clip);

  bool hasClip() const { return clip_ >= 0; }
  bool playing() const { return playing_; }
  // Play from the pose shown, or pause on it; false (nothing changes) without a clip.
  bool togglePlaying(Clock::time_point now);
  // While playing: the pose at `now` (the clip's time advances with the wall clock since the last
  // call, looping); true when `scene` was posed. Paused or without a clip: false, nothing moves.
  bool update(Clock::time_point now, Scene& scene);
  // Seconds into the clip (0 to its duration).
  double time() const { return time_; }
  // The overlay's line: "animation 'move' 1.25 / 2.00 s, playing".
  std::string describe() const;
  // What the space bar did, for stdout: "animation playing from 0.000 s" or "animation paused at
  // 1.250 s".
  std::string state() const;

 private:
  void pose(Scene& scene);

  SceneGraph graph_;
  int clip_ = -1;
  bool playing_ = false;
  double time_ = 0.0;
  Clock::time_point last_update_;
};

}  // namespace tessera::viewer
