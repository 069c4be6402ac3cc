// KHR_draco_mesh_compression, decoded with Debian's libdraco (gltf_draco.h): the extension's
// bufferView decoded by draco::Decoder, its counts checked against the budget and the accessors,
// then each attribute tessera reads converted to its accessor's component type so the builder
// reads it like any other accessor (gltf_reader.cpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#pragma GCC diagnostic pop

#include "gltf_accessors.h"
#include "gltf_draco.h"
#include "load_budget.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

// The glTF attributes tessera draws (gltf_primitives.cpp); the rest are not decoded.
bool drawnSemantic(const std::string& semantic) {
  return semantic == "POSITION" || semantic == "NORMAL" || semantic == "COLOR_0" ||
         semantic.starts_with("TEXCOORD_");
}

// `points` values of `attribute` as `components` values of T each, in point order.
template <typename T>
bool convertPoints(const draco::PointAttribute& attribute, size_t points, int components,
                   std::vector<uint8_t>& out) {
  out.resize(points * static_cast<size_t>(components) * sizeof(T));
  T values[4] = {};
  for (size_t i = 0; i < points; ++i) {
    const draco::AttributeValueIndex value =
        attribute.mapped_index(draco::PointIndex(static_cast<uint32_t>(i)));
    if (value.value() >= attribute.size()) return false;
    if (!attribute.ConvertValue<T>(value, static_cast<int8_t>(components), values)) return false;
    std::memcpy(out.data() + i * components * sizeof(T), values, components * sizeof(T));
  }
  return true;
}

bool convertAttribute(const draco::PointAttribute& attribute, size_t points, int components,
                      int component_type, std::vector<uint8_t>& out) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return convertPoints<int8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return convertPoints<uint8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return convertPoints<int16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return convertPoints<uint16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return convertPoints<uint32_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return convertPoints<float>(attribute, points, components, out);
    default:
      return false;
  }
}

// A warning when decoded positions fall outside the accessor's declared min/max by more than
// float rounding: tessera does not use the bounds, but a disagreement says the stream is not the
// one the file was written with.
void checkBounds(const tinygltf::Accessor& accessor, const DecodedAccessor& decoded,
                 const std::string& what, std::vector<std::string>& warnings) {
  if (decoded.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || accessor.minValues.size() < 3 ||
      accessor.maxValues.size() < 3 || decoded.count == 0)
    return;
  // The components per element as decoded (the accessor's type, which a file may get wrong: only
  // those the bytes hold are read).
  const size_t components = decoded.bytes.size() / (decoded.count * sizeof(float));
  if (components < 3) return;
  for (size_t i = 0; i < decoded.count; ++i) {
    for (size_t c = 0; c < 3; ++c) {
      float v;
      std::memcpy(&v, decoded.bytes.data() + (components * i + c) * sizeof(float), sizeof v);
      const double lo = accessor.minValues[c], hi = accessor.maxValues[c];
      const double slack = 1e-5 * std::max({1.0, std::abs(lo), std::abs(hi)});
      if (std::isfinite(v) && (v < lo - slack || v > hi + slack)) {
        warnings.push_back(what + ": decoded POSITION " + std::to_string(v) +
                           " lies outside the accessor's min/max");
        return;
      }
    }
  }
}

// Compares a decoded count with the accessor's declared one: more is an error, fewer a warning.
Expected<void> checkDeclared(const std::string& what, const std::string& role, uint64_t decoded,
                             uint64_t declared, std::vector<std::string>& warnings) {
  const std::string text = what + ": the Draco stream decodes to " + std::to_string(decoded) + " " +
                           role + ", the accessor declares " + std::to_string(declared);
  if (decoded > declared)
    return makeError(text + " (the budget was checked with the declared count)");
  if (decoded < declared) warnings.push_back(text + "; the decoded ones are drawn");
  return {};
}

// The decoded faces as glTF indices, in the decoder's face order.
Expected<void> readFaces(const draco::Mesh& mesh, const std::string& what, DracoPrimitive& out) {
  out.indices.resize(size_t{mesh.num_faces()} * 3);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(f));
    for (int c = 0; c < 3; ++c) {
      const uint32_t point = face[c].value();
      if (point >= out.points)
        return makeError(what + ": the Draco stream's face " + std::to_string(f) +
                         " refers to point " + std::to_string(point) + " of " +
                         std::to_string(out.points));
      out.indices[size_t{f} * 3 + static_cast<size_t>(c)] = point;
    }
  }
  return {};
}

// Each drawn attribute the extension lists, from the stream into `out.accessors`.
Expected<void> readAttributes(const tinygltf::Model& gltf, const tinygltf::Primitive& primitive,
                              const tinygltf::Value& attributes, const draco::Mesh& mesh,
                              const std::string& what, DracoPrimitive& out) {
  for (const auto& [semantic, id] : attributes.Get<tinygltf::Value::Object>()) {
    if (!drawnSemantic(semantic)) continue;
    auto it = primitive.attributes.find(semantic);
    if (it == primitive.attributes.end()) {
      out.warnings.push_back(what + ": the Draco stream's " + semantic +
                             " has no accessor in the primitive's attributes; it is ignored");
      continue;
    }
    if (it->second < 0 || static_cast<size_t>(it->second) >= gltf.accessors.size())
      continue;  // the builder refuses the accessor index
    const tinygltf::Accessor& accessor = gltf.accessors[static_cast<size_t>(it->second)];
    if (!id.IsInt() || id.Get<int>() < 0)
      return makeError(what + ": the Draco extension's " + semantic + " is not an attribute id");
    const draco::PointAttribute* attribute =
        mesh.GetAttributeByUniqueId(static_cast<uint32_t>(id.Get<int>()));
    if (attribute == nullptr)
      return makeError(what + ": the Draco stream has no attribute " +
                       std::to_string(id.Get<int>()) + " (" + semantic + ")");
    const int components = componentCount(accessor.type);
    if (components == 0 || componentBytes(accessor.componentType) == 0)
      continue;  // the builder refuses or ignores the accessor's type
    if (attribute->num_components() < components)
      return makeError(what + ": the Draco stream's " + semantic + " has " +
                       std::to_string(attribute->num_components()) +
                       " components, the accessor declares " + std::to_string(components));
    if (!attribute->is_mapping_identity() && attribute->indices_map_size() < out.points)
      return makeError(what + ": the Draco stream's " + semantic + " does not cover its points");
    if (Expected<void> ok = checkDeclared(what + ": " + semantic, "values", out.points,
                                          accessor.count, out.warnings);
        !ok)
      return ok;
    DecodedAccessor decoded;
    decoded.count = out.points;
    decoded.component_type = accessor.componentType;
    if (!convertAttribute(*attribute, out.points, components, accessor.componentType,
                          decoded.bytes))
      return makeError(what + ": the Draco stream's " + semantic + " cannot be read as " +
                       componentName(accessor.componentType) + " values");
    if (semantic == "POSITION") checkBounds(accessor, decoded, what, out.warnings);
    out.accessors[it->second] = std::move(decoded);
  }
  return {};
}

}  // namespace

bool dracoDecoderBuilt() {
  return true;
}

Expected<DracoPrimitive> decodeDracoPrimitive(const tinygltf::Model& gltf,
                                              const tinygltf::Primitive& primitive,
                                              const std::string& name, const std::string& where,
                                              const DracoBudget& budget) {
  const std::string what = name + ": " + where;
  const tinygltf::Value& extension = primitive.extensions.at(std::string(kDracoExtension));
  if (!extension.IsObject() || !extension.Get("bufferView").IsInt() ||
      !extension.Get("attributes").IsObject())
    return makeError(what + ": its " + std::string(kDracoExtension) +
                     " lacks a bufferView or attributes");
  Expected<std::span<const uint8_t>> bytes =
      viewBytes(gltf, extension.Get("bufferView").Get<int>(), what + ": the Draco stream");
  if (!bytes) return bytes.error();

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH)
    return makeError(what + ": the Draco stream (" + std::to_string(bytes->size()) +
                     " bytes) is not a Draco triangle mesh" +
                     (type.ok() ? std::string() : ": " + type.status().error_msg_string()));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok() || !decoded.value())
    return makeError(what + ": the Draco stream (" + std::to_string(bytes->size()) +
                     " bytes) cannot be decoded: " +
                     (decoded.ok() ? std::string("no mesh") : decoded.status().error_msg_string()));
  const draco::Mesh& mesh = *decoded.value();

  // The decoded counts against the budget, before tessera allocates anything for them.
  DracoPrimitive out;
  out.points = mesh.num_points();
  const uint64_t faces = mesh.num_faces();
  if (Expected<void> ok = checkBudget(name, "triangles (with the Draco stream of " + where + ")",
                                      budget.stored_triangles + faces, budget.budget.triangles(),
                                      "--max-triangles");
      !ok)
    return ok.error();
  if (Expected<void> ok = checkBudget(name, "vertices (with the Draco stream of " + where + ")",
                                      budget.stored_vertices + out.points, budget.budget.vertices(),
                                      "--max-triangles");
      !ok)
    return ok.error();
  if (primitive.indices >= 0 && static_cast<size_t>(primitive.indices) < gltf.accessors.size()) {
    const uint64_t declared = gltf.accessors[static_cast<size_t>(primitive.indices)].count;
    if (Expected<void> ok =
            checkDeclared(what + ": indices", "indices", faces * 3, declared, out.warnings);
        !ok)
      return ok.error();
  }
  if (Expected<void> ok = readFaces(mesh, what, out); !ok) return ok.error();
  if (Expected<void> ok =
          readAttributes(gltf, primitive, extension.Get("attributes"), mesh, what, out);
      !ok)
    return ok.error();
  for (std::string& warning : out.warnings)  // the builder's warnings name the file themselves
    if (warning.starts_with(name + ": ")) warning.erase(0, name.size() + 2);
  return out;
}

}  // namespace tessera::io::gltf
