// How long a cache line takes to go from one core to another and back: two threads, pinned to
// two cores, hand a flag to each other; the time per exchange is one round trip. On a shared host
// this moves by several times from hour to hour (125 to 550 ns on the VM of docs/perf.md), and
// everything the CPU renderer's two workers share (bins, records read by the other core, the
// pool's hand-offs) pays it, so bench/run_all.sh records it beside the worker scaling.
//
//   tessera_corelatency [CPU_A CPU_B] [--json]      (default: cores 0 and 1)
//
// Prints the median of 15 runs of 20,000 exchanges each, in nanoseconds.
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kRuns = 15;
constexpr int kExchanges = 20000;

bool pinTo(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

struct alignas(128) Flag {
  std::atomic<int> turn{0};  // 1: the partner's turn to answer, 0: the caller's
};

// One run: the mean round trip in nanoseconds, or a negative value if a thread could not be
// pinned.
double measure(int cpu_a, int cpu_b) {
  if (!pinTo(cpu_a)) return -1;
  Flag flag;
  std::atomic<int> partner_state{0};  // 0: starting, 1: pinned, -1: could not be pinned
  std::thread partner([&] {
    if (!pinTo(cpu_b)) {
      partner_state = -1;
      return;
    }
    partner_state = 1;
    for (int i = 0; i < kExchanges; ++i) {
      while (flag.turn.load(std::memory_order_acquire) != 1) {
      }
      flag.turn.store(0, std::memory_order_release);
    }
  });
  while (partner_state == 0) std::this_thread::yield();
  if (partner_state < 0) {
    partner.join();
    return -1;
  }
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kExchanges; ++i) {
    flag.turn.store(1, std::memory_order_release);
    while (flag.turn.load(std::memory_order_acquire) != 0) {
    }
  }
  const auto end = std::chrono::steady_clock::now();
  partner.join();
  return std::chrono::duration<double, std::nano>(end - start).count() / kExchanges;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> cpus;
  bool json = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--json") == 0) {
      json = true;
      continue;
    }
    char* end = nullptr;
    const long cpu = std::strtol(argv[i], &end, 10);
    if (end == argv[i] || *end != '\0' || cpu < 0 || cpu >= CPU_SETSIZE) {
      std::fprintf(stderr, "tessera_corelatency: '%s' is not a CPU number\n", argv[i]);
      return 2;
    }
    cpus.push_back(static_cast<int>(cpu));
  }
  if (cpus.empty()) cpus = {0, 1};
  if (cpus.size() != 2 || cpus[0] == cpus[1]) {
    std::fprintf(stderr,
                 "usage: tessera_corelatency [CPU_A CPU_B] [--json] (two different CPUs)\n");
    return 2;
  }
  std::vector<double> runs;
  for (int r = 0; r < kRuns; ++r) {
    const double ns = measure(cpus[0], cpus[1]);
    if (ns < 0) {
      std::fprintf(stderr, "tessera_corelatency: cannot run a thread on CPU %d and one on CPU %d\n",
                   cpus[0], cpus[1]);
      return 1;
    }
    runs.push_back(ns);
  }
  std::sort(runs.begin(), runs.end());
  const double median = runs[runs.size() / 2];
  if (json)
    std::printf(
        "{\"cpus\": \"%d,%d\", \"round_trip_ns\": %.0f, \"min_ns\": %.0f, \"max_ns\": %.0f}\n",
        cpus[0], cpus[1], median, runs.front(), runs.back());
  else
    std::printf(
        "CPU %d <-> CPU %d: a cache line's round trip takes %.0f ns (median of %d runs; "
        "%.0f to %.0f)\n",
        cpus[0], cpus[1], median, kRuns, runs.front(), runs.back());
  return 0;
}
