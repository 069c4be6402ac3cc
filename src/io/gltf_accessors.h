// glTF accessor types and typed reads from checked buffer ranges. Private to tessera_io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <tessera/base/expected.h>

namespace tinygltf {
class Model;
}

namespace tessera::io::gltf {

// Bytes of one component of a glTF 2.0 accessor component type; 0 for any other.
int componentBytes(int component_type);
// "unsigned short", for messages.
const char* componentName(int component_type);
// Components of an accessor type (SCALAR 1 ... VEC4 4); 0 for matrices.
int componentCount(int type);

// Whether `count` elements of `element` bytes, `stride` apart, starting at `offset`, fit in
// `length` bytes. Overflow-free for any inputs.
bool fits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t element, uint64_t length);

// Typed, checked reads from one accessor. Built only after its range has been checked against
// the buffer, so every read is inside it.
struct ElementReader {
  const uint8_t* data = nullptr;  // element 0
  size_t stride = 0;
  size_t count = 0;
  int components = 0;
  int component_type = 0;
  bool normalized = false;

  // Component `c` of `element`, normalized when the accessor says so.
  double raw(size_t element, int c) const;
  float component(size_t element, int c) const;
  // An index (unsigned byte, short or int).
  uint32_t index(size_t element) const;
};

// The checked byte range of a buffer view, or why it has none (`what` names the user).
Expected<std::span<const uint8_t>> viewBytes(const tinygltf::Model& gltf, int view_index,
                                             const std::string& what);

// A URI with its %XX escapes decoded.
std::string percentDecoded(std::string_view uri);

}  // namespace tessera::io::gltf
