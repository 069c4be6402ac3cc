// libFuzzer target for the OBJ reader (loadObj): the input is written to a scratch folder as
// fuzz.obj and loaded from there, so `mtllib` and texture references go through the real path
// checks. The folder also holds a small material library and texture for them to find.
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path& path = fuzz::scratchFolder("obj");
    const char* kMtl = "newmtl a\nKd 1 0 0\nmap_Kd t.png\nnewmtl b\nKd 0 1 0\n";
    fuzz::writeFile(path / "m.mtl", reinterpret_cast<const uint8_t*>(kMtl), std::strlen(kMtl));
    fuzz::writeTinyPng(path / "t.png");
    return path;
  }();
  const std::filesystem::path obj = folder / "fuzz.obj";
  fuzz::writeFile(obj, data, size);
  fuzz::checkModel(io::loadObj(obj));
  return 0;
}
