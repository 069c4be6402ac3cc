// libFuzzer target for the STL reader (binary and ASCII), straight from memory.
#include <cstdint>
#include <span>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  fuzz::checkModel(io::loadStlFromMemory(std::span(data, size), "fuzz.stl"));
  return 0;
}
