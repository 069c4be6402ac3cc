// libFuzzer target for the MTL reader: the input is written as fuzz.mtl beside a fixed OBJ that
// names it and uses each material the input declares (up to 16), so every material is built
// and its textures looked up. The folder holds a small texture for `map_Kd t.png` to find.
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  static const std::filesystem::path folder = [] {
    const std::filesystem::path& path = fuzz::scratchFolder("mtl");
    fuzz::writeTinyPng(path / "t.png");
    return path;
  }();
  fuzz::writeFile(folder / "fuzz.mtl", data, size);

  // One triangle per declared material (as tinyobjloader reads `newmtl NAME`).
  std::string obj = "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  size_t used = 0, begin = 0;
  while (begin < text.size() && used < 16) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(begin, end - begin);
    begin = end + 1;
    if (!line.starts_with("newmtl ")) continue;
    std::string name(line.substr(7));
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    if (name.empty() || name.find_first_of(std::string("\0\r", 2)) != std::string::npos) continue;
    obj += "usemtl " + name + "\nf 1/1 2/2 3/3\n";
    ++used;
  }
  obj += "usemtl\nf 1 2 3\n";
  const std::filesystem::path path = folder / "fuzz.obj";
  fuzz::writeFile(path, reinterpret_cast<const uint8_t*>(obj.data()), obj.size());
  fuzz::checkModel(io::loadObj(path));
  return 0;
}
