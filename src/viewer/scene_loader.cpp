#include <tessera/viewer/scene_loader.h>

#include <atomic>
#include <exception>
#include <new>
#include <thread>

namespace tessera::viewer {

struct SceneLoader::Job {
  std::thread thread;
  std::atomic<bool> done{false};
  // Written by the thread before `done` is set (release), read after it is seen (acquire).
  std::optional<Expected<LoadedScene>> result;
};

SceneLoader::SceneLoader() = default;

SceneLoader::~SceneLoader() {
  for (const std::unique_ptr<Job>& job : jobs_)
    if (job->thread.joinable()) job->thread.join();
}

void SceneLoader::start(std::string name, LoadFunction load) {
  TESSERA_CHECK(load) << "SceneLoader::start without a load function";
  name_ = std::move(name);
  auto job = std::make_unique<Job>();
  Job* raw = job.get();
  job->thread = std::thread([raw, load = std::move(load)] {
    try {
      raw->result.emplace(load());
    } catch (const std::bad_alloc&) {
      raw->result.emplace(makeError("out of memory while loading"));
    } catch (const std::exception& e) {
      raw->result.emplace(makeError(std::string("loading failed: ") + e.what()));
    }
    raw->done.store(true, std::memory_order_release);
  });
  latest_ = raw;
  jobs_.push_back(std::move(job));
}

std::optional<Expected<LoadedScene>> SceneLoader::takeResult() {
  std::optional<Expected<LoadedScene>> taken;
  if (latest_ != nullptr && latest_->done.load(std::memory_order_acquire)) {
    taken = std::move(latest_->result);
    latest_ = nullptr;
  }
  // Join and forget every finished job that is no longer the latest.
  for (size_t i = 0; i < jobs_.size();) {
    Job* job = jobs_[i].get();
    if (job != latest_ && job->done.load(std::memory_order_acquire)) {
      job->thread.join();
      jobs_.erase(jobs_.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
  return taken;
}

}  // namespace tessera::viewer
