// A fixed set of worker threads that run parallel-for loops. The calling thread takes part as
// worker 0, so a pool of one runs everything inline.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

namespace tessera::render {

class WorkerPool {
 public:
  // workers: 0 = one per hardware thread.
  explicit WorkerPool(int workers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int size() const { return static_cast<int>(threads_.size()) + 1; }

  // Calls body(index, worker) for every index in [0, count), spread over the workers; returns
  // when all are done. Worker w of n starts on its own block of indices, [count * w / n,
  // count * (w + 1) / n), in increasing order; a worker whose block is done helps with the
  // others', taking their next indices too. The same blocks go to the same workers stage after
  // stage and frame after frame, so what one stage writes (the vertices a range of triangles
  // uses, say) is mostly read by the same core in the next: on a host where a line takes
  // hundreds of nanoseconds between cores that is worth more than an even split (docs/perf.md,
  // round 5). Every block is handed out in increasing order, so a caller whose blocks end in
  // small pieces of work has its workers finish close together (round 6).
  template <typename Body>
  void parallelFor(size_t count, Body&& body) {
    auto invoke = [](void* context, size_t index, int worker) {
      (*static_cast<Body*>(context))(index, worker);
    };
    run(count, &body, invoke);
  }

 private:
  using Invoker = void (*)(void*, size_t, int);
  void run(size_t count, void* context, Invoker invoker);
  void workerLoop(int worker);
  void drain(int worker);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  // Written under mutex_, read without it by spinning threads.
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> busy_{0};
  std::atomic<bool> stopping_{false};

  // The indices of one worker's block not yet handed out, [front, back), as back << 32 | front.
  // A line of its own.
  struct alignas(128) Block {
    std::atomic<uint64_t> range{0};
  };
  // Takes the block's next index; false when none is left.
  bool take(Block& block, size_t& index);

  // The current job.
  void* context_ = nullptr;
  Invoker invoker_ = nullptr;
  std::vector<Block> blocks_;  // one per worker
};

}  // namespace tessera::render
