// The glTF builder's accessor reads: every accessor checked against its buffer view (type,
// component type, range, stride) before a byte is read; sparse and view-less accessors made
// dense once.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "gltf_builder.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

std::string GraphBuilder::accessorName(int accessor, const std::string& role) const {
  return name_ + ": accessor " + std::to_string(accessor) + " (" + role + ")";
}

// A reader for `accessor`, its type and component types checked against `allowed_types` and
// `allowed_components` (empty: any), and its range against its buffer view.
Expected<ElementReader> GraphBuilder::reader(int accessor_index, const std::string& role,
                                             std::initializer_list<int> allowed_types,
                                             std::initializer_list<int> allowed_components) {
  if (accessor_index < 0 || static_cast<size_t>(accessor_index) >= gltf_.accessors.size())
    return makeError(name_ + ": " + role + " refers to accessor " + std::to_string(accessor_index) +
                     ", but the file has " + std::to_string(gltf_.accessors.size()));
  const std::string what = accessorName(accessor_index, role);
  const tinygltf::Accessor& accessor = gltf_.accessors[static_cast<size_t>(accessor_index)];
  ElementReader reader;
  reader.components = componentCount(accessor.type);
  reader.component_type = accessor.componentType;
  reader.normalized = accessor.normalized;
  reader.count = accessor.count;
  const int component_bytes = componentBytes(accessor.componentType);
  if (component_bytes == 0)
    return makeError(what + ": component type " + std::to_string(accessor.componentType) +
                     " is not a glTF 2.0 accessor component type");
  if (std::find(allowed_types.begin(), allowed_types.end(), reader.components) ==
      allowed_types.end())
    return makeError(what + ": has " +
                     (reader.components == 0
                          ? std::string("a matrix type")
                          : std::to_string(reader.components) + " components per element") +
                     ", which this attribute cannot have");
  if (allowed_components.size() > 0 &&
      std::find(allowed_components.begin(), allowed_components.end(), accessor.componentType) ==
          allowed_components.end())
    return makeError(what + ": component type " + componentName(accessor.componentType) +
                     " is not allowed here");
  if (reader.count == 0) return makeError(what + ": count is 0");
  const size_t element = static_cast<size_t>(reader.components) * component_bytes;

  // A Draco primitive's attribute: the decoded values, converted to the declared type.
  if (draco_) {
    auto decoded = draco_->accessors.find(accessor_index);
    if (decoded != draco_->accessors.end()) {
      reader.data = decoded->second.bytes.data();
      reader.count = decoded->second.count;
      reader.stride = element;
      return reader;
    }
  }

  if (!accessor.sparse.isSparse && accessor.bufferView >= 0) {
    Expected<std::span<const uint8_t>> bytes = viewBytes(gltf_, accessor.bufferView, what);
    if (!bytes) return bytes.error();
    const tinygltf::BufferView& view = gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
    reader.stride = view.byteStride != 0 ? view.byteStride : element;
    if (reader.stride < element)
      return makeError(what + ": bufferView " + std::to_string(accessor.bufferView) +
                       " has byteStride " + std::to_string(view.byteStride) +
                       ", smaller than the " + std::to_string(element) + "-byte element");
    if (!fits(accessor.byteOffset, reader.count, reader.stride, element, bytes->size()))
      return makeError(what + ": " + std::to_string(reader.count) + " elements of " +
                       std::to_string(element) + " bytes, " + std::to_string(reader.stride) +
                       " apart from byte " + std::to_string(accessor.byteOffset) +
                       ", reach past the end of bufferView " + std::to_string(accessor.bufferView) +
                       " (" + std::to_string(bytes->size()) + " bytes)");
    reader.data = bytes->data() + accessor.byteOffset;
    return reader;
  }

  // Zeros, or a dense copy, with the sparse values written over it: built once per accessor.
  auto cached = dense_.find(accessor_index);
  if (cached == dense_.end()) {
    Expected<std::vector<uint8_t>> dense = densify(accessor, what, element);
    if (!dense) return dense.error();
    cached = dense_.emplace(accessor_index, std::move(dense).value()).first;
  }
  reader.data = cached->second.data();
  reader.stride = element;
  return reader;
}

Expected<std::vector<uint8_t>> GraphBuilder::densify(const tinygltf::Accessor& accessor,
                                                     const std::string& what, size_t element) {
  const size_t count = accessor.count;
  std::vector<uint8_t> dense;
  if (accessor.bufferView >= 0) {
    Expected<std::span<const uint8_t>> bytes = viewBytes(gltf_, accessor.bufferView, what);
    if (!bytes) return bytes.error();
    const tinygltf::BufferView& view = gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
    const size_t stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element)
      return makeError(what + ": bufferView byteStride " + std::to_string(view.byteStride) +
                       " is smaller than the " + std::to_string(element) + "-byte element");
    if (!fits(accessor.byteOffset, count, stride, element, bytes->size()))
      return makeError(what + ": " + std::to_string(count) +
                       " elements reach past the end of "
                       "bufferView " +
                       std::to_string(accessor.bufferView));
    dense.resize(count * element);
    for (size_t i = 0; i < count; ++i)
      std::memcpy(dense.data() + i * element, bytes->data() + accessor.byteOffset + i * stride,
                  element);
  } else {
    // count <= implied_bytes_left_ / element, checked without multiplying.
    if (count > implied_bytes_left_ / element)
      return makeError(what + ": " + std::to_string(count) +
                       " elements without a bufferView: more than the file's size can "
                       "justify");
    implied_bytes_left_ -= count * element;
    dense.assign(count * element, 0);
  }
  if (!accessor.sparse.isSparse) return dense;

  const auto& sparse = accessor.sparse;
  const std::string sparse_what = what + ": sparse";
  if (sparse.count <= 0 || static_cast<size_t>(sparse.count) > count)
    return makeError(sparse_what + " count " + std::to_string(sparse.count) +
                     " is not between 1 and the accessor's count " + std::to_string(count));
  const auto sparse_count = static_cast<size_t>(sparse.count);
  const int index_bytes = componentBytes(sparse.indices.componentType);
  if (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    return makeError(sparse_what + " indices must be unsigned byte, short or int");
  Expected<std::span<const uint8_t>> indices =
      viewBytes(gltf_, sparse.indices.bufferView, sparse_what);
  if (!indices) return indices.error();
  Expected<std::span<const uint8_t>> values =
      viewBytes(gltf_, sparse.values.bufferView, sparse_what);
  if (!values) return values.error();
  if (sparse.indices.byteOffset < 0 || !fits(static_cast<uint64_t>(sparse.indices.byteOffset),
                                             sparse_count, static_cast<uint64_t>(index_bytes),
                                             static_cast<uint64_t>(index_bytes), indices->size()))
    return makeError(sparse_what + " indices reach past the end of their bufferView");
  if (sparse.values.byteOffset < 0 || !fits(static_cast<uint64_t>(sparse.values.byteOffset),
                                            sparse_count, element, element, values->size()))
    return makeError(sparse_what + " values reach past the end of their bufferView");
  ElementReader index_reader;
  index_reader.data = indices->data() + sparse.indices.byteOffset;
  index_reader.stride = static_cast<size_t>(index_bytes);
  index_reader.count = sparse_count;
  index_reader.components = 1;
  index_reader.component_type = sparse.indices.componentType;
  const uint8_t* value_bytes = values->data() + sparse.values.byteOffset;
  for (size_t i = 0; i < sparse_count; ++i) {
    const uint32_t target = index_reader.index(i);
    if (target >= count)
      return makeError(sparse_what + " index " + std::to_string(target) +
                       " is past the accessor's " + std::to_string(count) + " elements");
    std::memcpy(dense.data() + size_t{target} * element, value_bytes + i * element, element);
  }
  return dense;
}

// An optional attribute: a reader, or nothing with a warning when it cannot be used.
std::optional<ElementReader> GraphBuilder::optionalAttribute(
    const tinygltf::Primitive& primitive, const std::string& semantic, const std::string& where,
    size_t vertex_count, std::initializer_list<int> types, std::initializer_list<int> components,
    Expected<void>& fatal) {
  auto it = primitive.attributes.find(semantic);
  if (it == primitive.attributes.end()) return std::nullopt;
  Expected<ElementReader> attribute =
      reader(it->second, semantic + " of " + where, types, components);
  if (!attribute) {
    // Out-of-range data is a broken file; an unusable type is only an unusable attribute.
    const std::string& message = attribute.error().message;
    if (message.find("past the end") != std::string::npos ||
        message.find("lies outside") != std::string::npos ||
        message.find("justify") != std::string::npos) {
      fatal = attribute.error();
      return std::nullopt;
    }
    warn(message.substr(name_.size() + 2) + "; " + semantic + " is ignored");
    return std::nullopt;
  }
  if (attribute->count != vertex_count) {
    warn(where + ": " + semantic + " has " + std::to_string(attribute->count) + " elements for " +
         std::to_string(vertex_count) + " positions; it is ignored");
    return std::nullopt;
  }
  return *attribute;
}

Expected<std::optional<ElementReader>> GraphBuilder::indexReader(
    const tinygltf::Primitive& primitive, const std::string& where) {
  if (primitive.indices < 0) return std::optional<ElementReader>{};
  Expected<ElementReader> read =
      reader(primitive.indices, "indices of " + where, {1},
             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
  if (!read) return read.error();
  return std::optional<ElementReader>{*read};
}

std::optional<ElementReader> GraphBuilder::colorAttribute(const tinygltf::Primitive& primitive,
                                                          const std::string& where,
                                                          size_t vertex_count,
                                                          Expected<void>& fatal) {
  return optionalAttribute(primitive, "COLOR_0", where, vertex_count, {3, 4},
                           {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                           fatal);
}

}  // namespace tessera::io::gltf
