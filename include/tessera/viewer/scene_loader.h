// Loads scenes on background threads so that the window keeps drawing while a large model is
// read. The latest load wins: starting another one drops the result of the one in flight.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

namespace tessera::viewer {

class SceneLoader {
 public:
  using LoadFunction = std::function<Expected<Scene>()>;

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
  std::optional<Expected<Scene>> takeResult();

 private:
  struct Job;
  std::vector<std::unique_ptr<Job>> jobs_;  // running or not yet joined
  Job* latest_ = nullptr;                   // in jobs_, or null once its result was taken
  std::string name_;
};

}  // namespace tessera::viewer
