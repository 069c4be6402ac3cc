// Checks made before tinygltf sees a glTF file: the GLB container (tinygltf's chunk bounds miss
// the 8-byte chunk header) and the JSON's shape (nesting depth, object count, images stored in
// buffer views outside their buffer, which tinygltf reads unchecked). Private to tessera_io.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <tessera/base/expected.h>

namespace tessera::io::gltf {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"

uint32_t readU32(const uint8_t* p);

// Checks the GLB header and chunk table so every read tinygltf makes is inside the file.
Expected<void> checkGlbContainer(std::span<const uint8_t> bytes, const std::string& name);

// Parses the JSON once, keeping only what the image check needs, and refuses shapes tinygltf
// cannot take safely: nesting too deep, too many objects, images whose buffer view lies outside
// its buffer (tinygltf reads those bytes unchecked).
Expected<void> checkJsonShape(std::string_view text, const std::string& name);

}  // namespace tessera::io::gltf
