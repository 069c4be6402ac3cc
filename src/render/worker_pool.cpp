#include "render/worker_pool.h"

namespace tessera::render {

WorkerPool::WorkerPool(int workers) {
  int total = workers > 0 ? workers : static_cast<int>(std::thread::hardware_concurrency());
  if (total < 1) total = 1;
  threads_.reserve(total - 1);
  for (int i = 1; i < total; ++i) threads_.emplace_back([this, i] { workerLoop(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void WorkerPool::drain(int worker) {
  for (;;) {
    size_t index = next_.fetch_add(1, std::memory_order_relaxed);
    if (index >= count_) return;
    invoker_(context_, index, worker);
  }
}

void WorkerPool::run(size_t count, void* context, Invoker invoker) {
  if (count == 0) return;
  if (threads_.empty() || count == 1) {
    for (size_t i = 0; i < count; ++i) invoker(context, i, 0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    context_ = context;
    invoker_ = invoker;
    count_ = count;
    next_.store(0, std::memory_order_relaxed);
    busy_ = static_cast<int>(threads_.size());
    ++generation_;
  }
  wake_.notify_all();
  drain(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return busy_ == 0; });
}

void WorkerPool::workerLoop(int worker) {
  uint64_t seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
    }
    drain(worker);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

}  // namespace tessera::render
