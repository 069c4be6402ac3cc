// Loads scenes on background threads so that the window keeps drawing while a large model is
// read. The latest load wins: starting another one drops the result of the one in flight.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/graph.h>
#include <tessera/scene/scene.h>

namespace tessera::viewer {

// What a load gives the viewer: the scene, and the scene graph it was made from, whose clips the
// space bar plays and whose cameras --camera-index picks (an empty graph for a scene without one).
struct LoadedScene {
  Scene scene;
  SceneGraph graph;
  int clip = -1;  // the clip to play (into graph.animations), -1 none: prepareClip()
  Bounds bounds;  // what the camera frames: the scene's, and every pose of the clip
};

// A scene that comes without a graph (nothing to play, no cameras), framed by its own bounds.
inline LoadedScene withoutGraph(Scene scene) {
  LoadedScene loaded;
  loaded.scene = std::move(scene);
  loaded.bounds = loaded.scene.bounds();
  return loaded;
}

class SceneLoader {
 public:
  using LoadFunction = std::function<Expected<LoadedScene>()>;

  SceneLoader();
  // Waits for every thread still running (a load cannot be cancelled half-way).
  ~SceneLoader();
  SceneLoader(const SceneLoader&) = delete;
  SceneLoader& operator=(const SceneLoader&) = delete;

  // Runs `load` on a new thread; `name` is what the window shows while it runs. An exception
  // thrown by `load` (out of memory) becomes an error result.
  void start(std::string name, LoadFunction load);
  // The latest load is running, or has finished and its result is waiting for takeResult().
  // (A caller that polls while busy() never misses a result that lands between two polls.)
  bool busy() const { return latest_ != nullptr; }
  // The name given to the latest start().
  const std::string& name() const { return name_; }
  // The latest load's result, once, when it has finished; nullopt while it runs (or after the
  // result was taken). Also joins the threads of superseded loads that have ended.
  std::optional<Expected<LoadedScene>> takeResult();

 private:
  struct Job;
  std::vector<std::unique_ptr<Job>> jobs_;  // running or not yet joined
  Job* latest_ = nullptr;                   // in jobs_, or null once its result was taken
  std::string name_;
};

}  // namespace tessera::viewer
