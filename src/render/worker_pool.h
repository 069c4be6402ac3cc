// A fixed set of worker threads that run parallel-for loops. The calling thread takes part as
// worker 0, so a pool of one runs everything inline.
//
// On Linux, where the thread that makes the pool may run on at least as many CPUs as the pool has
// threads, each worker thread is pinned to a CPU of its own, one the caller is not on; the caller
// is left free, and a loop that finds it on a worker's CPU gives that worker the CPU the caller
// left. Left to the scheduler, on this project's 2-core virtual machines, a run of 2-worker frames
// was at times 2.5 times slower for spells of tens to hundreds of frames, and every few tens of
// frames one took 6 ms more; pinned, neither happened (docs/perf-notes/speed-2026-12-07.md, "Worker
// threads pinned"). TESSERA_PIN_WORKERS=0 turns it off.
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
  // hundreds of nanoseconds between cores that is worth more than an even split
  // (docs/perf-notes/frame-stages.md, round 5). Every block is handed out in increasing order, so
  // a caller whose blocks end in small pieces of work has its workers finish close together
  // (round 6).
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
  // Where the caller has moved onto a worker's CPU, moves that worker to the CPU it left.
  void keepCallerApart();

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
  // The caller's CPU when a loop last started, then the one each worker thread is pinned to
  // (threads_[i] to cpus_[i + 1]); empty where no thread is pinned.
  std::vector<int> cpus_;
};

}  // namespace tessera::render
