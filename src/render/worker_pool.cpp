#include "render/worker_pool.h"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include <tessera/base/check.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif
#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

namespace tessera::render {

namespace {

// How long a thread spins before it sleeps. Stages follow one another within microseconds, but
// one worker may finish its part of a stage a setup chunk (100 us or more) before the other,
// and a sleeping thread took 10-30 us to wake on this VM: with a 50 us spin the tile stage
// started that much late every frame (docs/perf-notes/frame-stages.md, round 6). Measured in time,
// not pause instructions, whose length differs between processors by ten times.
constexpr std::chrono::microseconds kSpinTime{250};

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#endif
}

// Spins until ready() or kSpinTime has passed; whether ready() was seen.
template <typename Ready>
bool spinUntil(Ready&& ready) {
  const auto until = std::chrono::steady_clock::now() + kSpinTime;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (ready()) return true;
      pause();
    }
    if (std::chrono::steady_clock::now() >= until) return false;
  }
}

// The CPUs of a pool of `total` threads: the caller's current one first (left to the caller,
// which is not pinned), then one for each worker thread, from the CPUs the caller may run on (the
// workers' own, which they inherit). Empty (no thread pinned) where those are fewer than `total`,
// with TESSERA_PIN_WORKERS=0, or off Linux.
std::vector<int> poolCpus(int total) {
#if defined(__linux__)
  const char* off = std::getenv("TESSERA_PIN_WORKERS");
  if (total < 2 || (off != nullptr && std::string_view(off) == "0")) return {};
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return {};
  const int here = sched_getcpu();
  std::vector<int> cpus;
  if (here >= 0 && here < CPU_SETSIZE && CPU_ISSET(here, &allowed)) cpus.push_back(here);
  for (int cpu = 0; cpu < CPU_SETSIZE && static_cast<int>(cpus.size()) < total; ++cpu)
    if (CPU_ISSET(cpu, &allowed) && cpu != here) cpus.push_back(cpu);
  if (static_cast<int>(cpus.size()) < total) return {};
  return cpus;
#else
  (void)total;
  return {};
#endif
}

// Pins `thread` to `cpu`; false where the system refused.
bool pinThread(std::thread& thread, int cpu) {
#if defined(__linux__)
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  return pthread_setaffinity_np(thread.native_handle(), sizeof one, &one) == 0;
#else
  (void)thread;
  (void)cpu;
  return false;
#endif
}

}  // namespace

WorkerPool::WorkerPool(int workers) {
  int total = workers > 0 ? workers : static_cast<int>(std::thread::hardware_concurrency());
  if (total < 1) total = 1;
  blocks_ = std::vector<Block>(static_cast<size_t>(total));
  threads_.reserve(total - 1);
  for (int i = 1; i < total; ++i) threads_.emplace_back([this, i] { workerLoop(i); });
  cpus_ = poolCpus(total);
  for (size_t i = 0; i < threads_.size() && !cpus_.empty(); ++i)
    if (!pinThread(threads_[i], cpus_[i + 1])) cpus_.clear();  // (a CPU gone): no more pinning
}

void WorkerPool::keepCallerApart() {
#if defined(__linux__)
  if (cpus_.empty()) return;
  const int here = sched_getcpu();  // read without a system call (rseq or the vDSO)
  if (here == cpus_[0] || here < 0) return;
  for (size_t i = 1; i < cpus_.size(); ++i) {
    if (cpus_[i] != here) continue;
    // The caller moved onto worker i's CPU: the worker takes the one the caller left.
    if (!pinThread(threads_[i - 1], cpus_[0])) return;
    cpus_[i] = cpus_[0];
    break;
  }
  cpus_[0] = here;
#endif
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_.store(true, std::memory_order_release);
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

bool WorkerPool::take(Block& block, size_t& index) {
  uint64_t range = block.range.load(std::memory_order_relaxed);
  for (;;) {
    const uint32_t front = static_cast<uint32_t>(range), back = static_cast<uint32_t>(range >> 32);
    if (front >= back) return false;
    if (block.range.compare_exchange_weak(range, range + 1, std::memory_order_relaxed)) {
      index = front;
      return true;
    }
  }
}

void WorkerPool::drain(int worker) {
  // Its own block first, then the others' (from their fronts too: taking from the back, a helper
  // took a block's last and smallest pieces first and left its owner on a large one, 40-80 us
  // after the helper ran out, docs/perf-notes/frame-stages.md, round 6).
  const size_t n = blocks_.size();
  size_t index;
  for (size_t k = 0; k < n; ++k) {
    Block& block = blocks_[(static_cast<size_t>(worker) + k) % n];
    while (take(block, index)) invoker_(context_, index, worker);
  }
}

void WorkerPool::run(size_t count, void* context, Invoker invoker) {
  if (count == 0) return;
  if (threads_.empty() || count == 1) {
    for (size_t i = 0; i < count; ++i) invoker(context, i, 0);
    return;
  }
  keepCallerApart();
  TESSERA_CHECK(count <= UINT32_MAX) << "a parallel loop of " << count << " indices";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    context_ = context;
    invoker_ = invoker;
    const size_t n = blocks_.size();
    for (size_t w = 0; w < n; ++w)
      blocks_[w].range.store(static_cast<uint64_t>(count * (w + 1) / n) << 32 | (count * w / n),
                             std::memory_order_relaxed);
    busy_.store(static_cast<int>(threads_.size()), std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  drain(0);
  if (spinUntil([this] { return busy_.load(std::memory_order_acquire) == 0; })) return;
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return busy_.load(std::memory_order_acquire) == 0; });
}

void WorkerPool::workerLoop(int worker) {
  uint64_t seen = 0;
  for (;;) {
    auto ready = [&] {
      return stopping_.load(std::memory_order_acquire) ||
             generation_.load(std::memory_order_acquire) != seen;
    };
    if (!spinUntil(ready)) {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, ready);
    }
    if (stopping_.load(std::memory_order_acquire)) return;
    seen = generation_.load(std::memory_order_acquire);
    drain(worker);
    if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      // Under the mutex: the caller may be between its check and its wait.
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}

}  // namespace tessera::render
