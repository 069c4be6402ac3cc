// libFuzzer target for the formats read through assimp (loadAssimpFromMemory): the sandbox, the
// header checks, assimp's PLY, OFF and COLLADA readers and the scene builder. assimp itself is
// the system library, not instrumented for coverage: the fuzzer steers by tessera's side. The
// format hint is taken from the bytes, so that one corpus reaches the three readers.
#include <cstdint>
#include <cstring>
#include <span>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  const char* name = "fuzz.off";
  if (size >= 3 && std::memcmp(data, "ply", 3) == 0)
    name = "fuzz.ply";
  else if (size >= 1 && data[0] == '<')
    name = "fuzz.dae";
  // A small budget: the counts it bounds are checked before assimp or tessera allocate.
  io::LoadBudget budget;
  budget.memory_bytes = uint64_t{64} << 20;
  fuzz::checkModel(io::loadAssimpFromMemory(std::span(data, size), name, budget));
  return 0;
}
