// libFuzzer target for the glTF/GLB reader, from memory. External buffers and images resolve
// beneath a scratch folder holding a small buffer (b.bin) and texture (t.png), so the file
// callbacks and path checks are exercised too.
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path& path = fuzz::scratchFolder("gltf");
    // One triangle: three float positions, then uint16 indices 0 1 2 and padding.
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<uint8_t> buffer(sizeof positions + 8, 0);
    std::memcpy(buffer.data(), positions, sizeof positions);
    const uint16_t indices[3] = {0, 1, 2};
    std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
    fuzz::writeFile(path / "b.bin", buffer.data(), buffer.size());
    fuzz::writeTinyPng(path / "t.png");
    return path;
  }();
  fuzz::checkModel(io::loadGltfFromMemory(std::span(data, size), "fuzz.gltf", folder));
  return 0;
}
