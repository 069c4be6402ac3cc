#include "gltf_accessors.h"

#include <algorithm>
#include <cstring>

#include "gltf_transforms.h"

#include "tinygltf_include.h"

namespace tessera::io::gltf {

int componentBytes(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}

const char* componentName(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "float";
    default:
      return "an invalid component type";
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;  // matrices: never a vertex attribute tessera reads
  }
}

// Whether `count` elements of `element` bytes, `stride` apart, starting at `offset`, fit in
// `length` bytes. Overflow-free for any inputs.
bool fits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t element, uint64_t length) {
  if (count == 0) return offset <= length;
  if (offset > length || element > length - offset) return false;
  return count - 1 <= (length - offset - element) / stride;
}

double ElementReader::raw(size_t element, int c) const {
  const uint8_t* p =
      data + element * stride + static_cast<size_t>(c) * componentBytes(component_type);
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

float ElementReader::component(size_t element, int c) const {
  return toFloat(raw(element, c));
}

uint32_t ElementReader::index(size_t element) const {
  const uint8_t* p = data + element * stride;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

std::string percentDecoded(std::string_view uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

Expected<std::span<const uint8_t>> viewBytes(const tinygltf::Model& gltf, int view_index,
                                             const std::string& what) {
  if (view_index < 0 || static_cast<size_t>(view_index) >= gltf.bufferViews.size())
    return makeError(what + " refers to bufferView " + std::to_string(view_index) +
                     ", but the file has " + std::to_string(gltf.bufferViews.size()));
  const tinygltf::BufferView& view = gltf.bufferViews[static_cast<size_t>(view_index)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= gltf.buffers.size())
    return makeError(what + ": bufferView " + std::to_string(view_index) + " refers to buffer " +
                     std::to_string(view.buffer) + ", but the file has " +
                     std::to_string(gltf.buffers.size()));
  const std::vector<unsigned char>& data = gltf.buffers[static_cast<size_t>(view.buffer)].data;
  if (!fits(view.byteOffset, 1, 1, view.byteLength, data.size()))
    return makeError(what + ": bufferView " + std::to_string(view_index) + " (bytes " +
                     std::to_string(view.byteOffset) + " to " +
                     std::to_string(uint64_t{view.byteOffset} + view.byteLength) +
                     ") lies outside buffer " + std::to_string(view.buffer) + " (" +
                     std::to_string(data.size()) + " bytes)");
  return std::span<const uint8_t>(data.data() + view.byteOffset, view.byteLength);
}

}  // namespace tessera::io::gltf
