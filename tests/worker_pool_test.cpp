// The worker pool's threads and CPUs: each worker thread pinned to a CPU of its own, away from the
// caller's, and moved when the caller comes onto its CPU (src/render/worker_pool.h). Linux only
// (tests/CMakeLists.txt), as the pinning is.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <pthread.h>
#include <sched.h>

#include "render/worker_pool.h"

namespace tessera {
namespace {

// The CPUs the calling thread may run on.
std::vector<int> allowedCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(pthread_getaffinity_np(pthread_self(), sizeof set, &set), 0);
  std::vector<int> cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &set)) cpus.push_back(cpu);
  return cpus;
}

void setAllowed(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int cpu : cpus) CPU_SET(cpu, &set);
  ASSERT_EQ(pthread_setaffinity_np(pthread_self(), sizeof set, &set), 0);
}

// What worker 1 saw of itself in a loop: the CPUs it may run on, and the CPU it ran on.
struct WorkerSeen {
  std::vector<int> allowed;
  int ran_on = -1;
};

// A loop of two indices of 5 ms for each worker: worker 1 (woken within microseconds) starts on
// its own two, where it records what it sees.
WorkerSeen seenByWorker(render::WorkerPool& pool) {
  WorkerSeen seen;
  std::atomic<int> worker_runs{0};
  pool.parallelFor(2 * static_cast<size_t>(pool.size()), [&](size_t, int worker) {
    if (worker == 1 && worker_runs.fetch_add(1) == 0) {
      seen.allowed = allowedCpus();
      seen.ran_on = sched_getcpu();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  EXPECT_GT(worker_runs.load(), 0) << "worker 1 took no index of the loop";
  return seen;
}

// Sets an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
      old_ = old;
      had_ = true;
    }
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_)
      setenv(name_, old_.c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

TEST(WorkerPool, WorkersArePinnedAwayFromTheCaller) {
  const std::vector<int> cpus = allowedCpus();
  ScopedEnv on("TESSERA_PIN_WORKERS", "1");
  render::WorkerPool pool(2);
  WorkerSeen seen = seenByWorker(pool);
  if (cpus.size() < 2) {
    // One CPU for two threads: nothing is pinned (what NothingIsPinnedWithMoreWorkersThanCpus
    // asks of any machine); the moves below need a second CPU.
    EXPECT_EQ(seen.allowed, cpus);
    return;
  }
  // The worker is pinned to one CPU, and runs there.
  ASSERT_EQ(seen.allowed.size(), 1u);
  EXPECT_EQ(seen.ran_on, seen.allowed[0]);
  // The caller moved onto the worker's CPU (twice, the second time onto the worker's new one):
  // each loop after finds the worker pinned elsewhere, and running there.
  for (int move = 0; move < 2; ++move) {
    const int worker_cpu = seen.allowed[0];
    setAllowed({worker_cpu});
    seen = seenByWorker(pool);
    ASSERT_EQ(seen.allowed.size(), 1u) << "move " << move;
    EXPECT_NE(seen.allowed[0], worker_cpu) << "move " << move;
    EXPECT_EQ(seen.ran_on, seen.allowed[0]) << "move " << move;
  }
  setAllowed(cpus);
}

TEST(WorkerPool, NothingIsPinnedWhenAskedNotTo) {
  const std::vector<int> cpus = allowedCpus();
  ScopedEnv off("TESSERA_PIN_WORKERS", "0");
  render::WorkerPool pool(2);
  EXPECT_EQ(seenByWorker(pool).allowed, cpus);
}

TEST(WorkerPool, NothingIsPinnedWithMoreWorkersThanCpus) {
  const std::vector<int> cpus = allowedCpus();
  ScopedEnv on("TESSERA_PIN_WORKERS", "1");
  render::WorkerPool pool(static_cast<int>(cpus.size()) + 1);
  EXPECT_EQ(seenByWorker(pool).allowed, cpus);
}

}  // namespace
}  // namespace tessera
