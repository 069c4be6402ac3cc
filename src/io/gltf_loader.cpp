// glTF 2.0 (JSON and GLB) through tinygltf. tinygltf parses the JSON and gathers the buffers;
// everything it hands back is checked here before a byte of a buffer is read, the node graph is
// flattened here in the contract's order, and every file the model refers to is opened here (or
// through the file callbacks below), only from beneath the model's folder.
//
// tinygltf trusts its input in two places, so two checks run before it sees a file: the GLB
// container (its chunk bounds miss the 8-byte chunk header) and images stored in buffer views
// (it takes their bytes without checking the view's range). A light scan of the JSON also bounds
// the nesting depth (tinygltf converts `extras` recursively) and the number of JSON objects
// (each becomes a large tinygltf struct).
#include <tessera/io/model_loader.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <tessera/io/image_loader.h>

#include "model_paths.h"

// Images are decoded by tessera's own decoder (image_loader.cpp); files are opened only through
// the callbacks installed below.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

namespace tessera::io {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// tinygltf takes lengths as unsigned int; 2 GiB keeps every offset well inside that.
constexpr uintmax_t kMaxGltfBytes = uintmax_t{2} << 30;
constexpr uintmax_t kMaxBufferFileBytes = uintmax_t{2} << 30;
// JSON shape: far beyond real files, far below what tinygltf's recursion and memory can take.
constexpr int kMaxJsonDepth = 64;
constexpr size_t kMaxJsonContainers = size_t{1} << 22;
// tinygltf turns each JSON object into a struct of its own, up to 2 KiB (a material) for as
// little as 3 bytes of text ("{},"). Files whose objects would take more than this are refused;
// a large real scene takes a few hundred MiB at most.
constexpr uint64_t kMaxParsedBytes = uint64_t{1} << 30;
// The flattened scene. Instancing can multiply a small file into a huge mesh; past this many
// triangles or vertices the file is refused rather than eating the machine.
constexpr size_t kMaxTriangles = size_t{1} << 25;
constexpr size_t kMaxVertices = size_t{1} << 25;
// Mesh::triangle_materials holds uint16_t.
constexpr size_t kMaxMaterials = size_t{1} << 16;
// 2 GiB of RGBA8 over all of a model's textures.
constexpr size_t kMaxTotalTexels = size_t{1} << 29;
constexpr size_t kMaxWarnings = 20;

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

// ---- Before tinygltf: the GLB container and the JSON's shape ----

uint32_t readU32(const uint8_t* p) {
  static_assert(std::endian::native == std::endian::little, "GLB is little-endian");
  uint32_t value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

// Checks the GLB header and chunk table so every read tinygltf makes is inside the file.
Expected<void> checkGlbContainer(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string truncated = name + ": truncated GLB: ";
  if (bytes.size() < 12)
    return makeError(truncated + std::to_string(bytes.size()) +
                     " bytes, shorter than the 12-byte header");
  const uint32_t version = readU32(bytes.data() + 4);
  const uint32_t length = readU32(bytes.data() + 8);
  if (version != 2)
    return makeError(name + ": GLB version " + std::to_string(version) +
                     "; only glTF 2.0 is supported");
  if (length > bytes.size())
    return makeError(truncated + "the header says " + std::to_string(length) +
                     " bytes, the file has " + std::to_string(bytes.size()));
  if (length < 20) return makeError(truncated + "no JSON chunk");
  const uint64_t json_length = readU32(bytes.data() + 12);
  if (readU32(bytes.data() + 16) != kChunkJson)
    return makeError(name + ": corrupt GLB: the first chunk is not JSON");
  const uint64_t json_end = 20 + json_length;
  if (json_length == 0 || json_end > length)
    return makeError(truncated + "the JSON chunk claims " + std::to_string(json_length) +
                     " bytes, " + std::to_string(length - 20) + " are left");
  if (json_end == length) return {};  // no binary chunk
  if (json_end + 8 > length) return makeError(truncated + "the binary chunk's header is cut off");
  const uint64_t bin_length = readU32(bytes.data() + json_end);
  if (readU32(bytes.data() + json_end + 4) != kChunkBin)
    return makeError(name + ": corrupt GLB: the second chunk is not BIN");
  if (json_end + 8 + bin_length > length)
    return makeError(truncated + "the binary chunk claims " + std::to_string(bin_length) +
                     " bytes, " + std::to_string(length - json_end - 8) + " are left");
  return {};
}

// Thrown from the JSON scan's callback to stop at the first sign of a hostile shape.
struct JsonShapeError {
  std::string message;
};

// An integer as tinygltf reads one into an int (ParseIntegerProperty): any JSON integer,
// truncated to int.
std::optional<int> gltfInt(const Json& object, const char* key) {
  auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer()) return std::nullopt;
  return static_cast<int>(it->get<int64_t>());
}

// An unsigned size as tinygltf reads one (ParseUnsignedProperty): only non-negative integers.
std::optional<uint64_t> gltfSize(const Json& object, const char* key) {
  auto it = object.find(key);
  if (it == object.end() || !it->is_number_unsigned()) return std::nullopt;
  return it->get<uint64_t>();
}

// What tinygltf allocates for one element of a top-level array.
uint64_t structBytes(const std::string& top_key) {
  if (top_key == "materials") return sizeof(tinygltf::Material);
  if (top_key == "nodes") return sizeof(tinygltf::Node);
  if (top_key == "accessors") return sizeof(tinygltf::Accessor);
  if (top_key == "meshes") return sizeof(tinygltf::Mesh);
  if (top_key == "images") return sizeof(tinygltf::Image);
  if (top_key == "textures") return sizeof(tinygltf::Texture);
  if (top_key == "bufferViews") return sizeof(tinygltf::BufferView);
  if (top_key == "buffers") return sizeof(tinygltf::Buffer);
  if (top_key == "samplers") return sizeof(tinygltf::Sampler);
  if (top_key == "scenes") return sizeof(tinygltf::Scene);
  return sizeof(tinygltf::Camera);  // the largest of the rest (animations, skins, cameras)
}

// Parses the JSON once, keeping only what the image check needs, and refuses shapes tinygltf
// cannot take safely: nesting too deep, too many objects, images whose buffer view lies outside
// its buffer (tinygltf reads those bytes unchecked).
Expected<void> checkJsonShape(std::string_view text, const std::string& name) {
  size_t containers = 0;
  uint64_t parsed_bytes = 0;
  std::string top_key;  // the key at depth 1: what an object at depth 2 will become
  auto keep = [&](int depth, Json::parse_event_t event, Json& parsed) -> bool {
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        if (depth >= kMaxJsonDepth)
          throw JsonShapeError{"the JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                               " levels"};
        if (++containers > kMaxJsonContainers)
          throw JsonShapeError{"the JSON has more than " + std::to_string(kMaxJsonContainers) +
                               " objects and arrays"};
        // The JSON value itself and tinygltf's copy of it (extras become tinygltf::Values).
        parsed_bytes += 256;
        if (event == Json::parse_event_t::object_start && depth == 2)
          parsed_bytes += structBytes(top_key);
        // Objects in the arrays of those: primitives, animation channels and samplers.
        if (event == Json::parse_event_t::object_start && depth == 4)
          parsed_bytes += std::max(sizeof(tinygltf::Primitive), sizeof(tinygltf::AnimationChannel));
        if (parsed_bytes > kMaxParsedBytes)
          throw JsonShapeError{"the JSON describes more objects than tessera parses (over " +
                               std::to_string(kMaxParsedBytes >> 20) +
                               " MiB of parser structures)"};
        return true;
      case Json::parse_event_t::key:
        if (depth == 1) {
          top_key = parsed.get<std::string>();
          return parsed == "images" || parsed == "bufferViews" || parsed == "buffers";
        }
        if (depth == 3)
          return parsed == "bufferView" || parsed == "buffer" || parsed == "byteOffset" ||
                 parsed == "byteLength";
        return true;
      default:
        return true;
    }
  };
  Json root;
  try {
    root = Json::parse(text.begin(), text.end(), keep, /*allow_exceptions=*/true,
                       /*ignore_comments=*/false);
  } catch (const JsonShapeError& error) {
    return makeError(name + ": " + error.message);
  } catch (const Json::parse_error& error) {
    // "[json.exception.parse_error.101] parse error at line 3, column 7: ..."
    std::string what = error.what();
    size_t at = what.find("] ");
    return makeError(name +
                     ": not valid JSON: " + (at == std::string::npos ? what : what.substr(at + 2)));
  }
  if (!root.is_object()) return makeError(name + ": the JSON is not an object: not glTF");
  auto arrayOf = [&](const char* key) -> const Json* {
    auto it = root.find(key);
    return it != root.end() && it->is_array() ? &*it : nullptr;
  };
  const Json* images = arrayOf("images");
  const Json* views = arrayOf("bufferViews");
  const Json* buffers = arrayOf("buffers");
  if (!images || !views || !buffers) return {};
  for (size_t i = 0; i < images->size(); ++i) {
    const Json& image = (*images)[i];
    if (!image.is_object()) continue;
    std::optional<int> view_index = gltfInt(image, "bufferView");
    if (!view_index || *view_index < 0 || static_cast<size_t>(*view_index) >= views->size())
      continue;  // tinygltf refuses these itself
    const Json& view = (*views)[static_cast<size_t>(*view_index)];
    if (!view.is_object()) continue;
    std::optional<int> buffer_index = gltfInt(view, "buffer");
    std::optional<uint64_t> view_length = gltfSize(view, "byteLength");
    if (!buffer_index || !view_length || *buffer_index < 0 ||
        static_cast<size_t>(*buffer_index) >= buffers->size())
      continue;
    const Json& buffer = (*buffers)[static_cast<size_t>(*buffer_index)];
    if (!buffer.is_object()) continue;
    // Once loaded, a buffer holds exactly byteLength bytes (tinygltf checks).
    std::optional<uint64_t> buffer_length = gltfSize(buffer, "byteLength");
    if (!buffer_length) continue;
    const uint64_t offset = gltfSize(view, "byteOffset").value_or(0);
    if (offset > *buffer_length || *view_length > *buffer_length - offset)
      return makeError(name + ": image " + std::to_string(i) + " is stored in bufferView " +
                       std::to_string(*view_index) + " (bytes " + std::to_string(offset) + " to " +
                       std::to_string(offset + *view_length) + "), which lies outside buffer " +
                       std::to_string(*buffer_index) + " (" + std::to_string(*buffer_length) +
                       " bytes)");
  }
  return {};
}

// ---- Files, through tinygltf's callbacks ----

// tinygltf joins a buffer's URI to the base folder it is given, then also tries ".". The base
// passed to it is this marker, so the callbacks can tell the URI from the attempt in "." (which
// they refuse) and resolve it themselves beneath the model's folder.
constexpr std::string_view kFolderMarker = "<tessera-model-folder>/";

struct ExternalFiles {
  fs::path folder;  // empty: nothing may be opened
  std::string model_name;
  std::vector<std::string> refusals;  // why a URI was refused, for the error message
  uintmax_t bytes_read = 0;

  Expected<fs::path> resolve(const std::string& joined) {
    if (!std::string_view(joined).starts_with(kFolderMarker))
      return makeError("only files beneath the model's folder are read");
    const std::string reference = joined.substr(kFolderMarker.size());
    if (folder.empty())
      return makeError("'" + reference +
                       "' is an external file, and this model was given in memory");
    Expected<fs::path> path = resolveReferencedFile(folder, reference);
    if (!path) return makeError("'" + reference + "' refused: " + path.error().message);
    return path;
  }
};

bool fileExists(const std::string& joined, void* user) {
  auto& files = *static_cast<ExternalFiles*>(user);
  // The second attempt, in ".", is never honoured and needs no second message.
  if (!std::string_view(joined).starts_with(kFolderMarker)) return false;
  Expected<fs::path> path = files.resolve(joined);
  if (!path) {
    files.refusals.push_back(path.error().message);
    return false;
  }
  std::error_code error;
  if (!fs::is_regular_file(*path, error)) {
    files.refusals.push_back(path->string() + ": no such file");
    return false;
  }
  return true;
}

std::string expandFilePath(const std::string& path, void*) {
  return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& joined,
                   void* user) {
  auto& files = *static_cast<ExternalFiles*>(user);
  Expected<fs::path> path = files.resolve(joined);
  if (!path) {
    files.refusals.push_back(path.error().message);
    if (err) *err = path.error().message;
    return false;
  }
  Expected<std::vector<unsigned char>> bytes = readModelFile(*path, kMaxBufferFileBytes, "buffer");
  if (!bytes) {
    files.refusals.push_back(bytes.error().message);
    if (err) *err = bytes.error().message;
    return false;
  }
  files.bytes_read += bytes->size();
  *out = std::move(bytes).value();
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "tessera never writes glTF files";
  return false;
}

// Keeps the encoded bytes of images given as data: URIs; images in buffer views are read from
// the buffer later, and only images a material uses are decoded.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes != nullptr && size > 0)
    image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// ---- Small maths, in double: node matrices compose over deep hierarchies ----

struct Matrix {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
  double at(int row, int column) const { return m[static_cast<size_t>(column * 4 + row)]; }
  double& at(int row, int column) { return m[static_cast<size_t>(column * 4 + row)]; }
};

Matrix operator*(const Matrix& a, const Matrix& b) {
  Matrix r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.at(row, k) * b.at(k, c);
      r.at(row, c) = sum;
    }
  return r;
}

double determinant3(const Matrix& a) {
  return a.at(0, 0) * (a.at(1, 1) * a.at(2, 2) - a.at(1, 2) * a.at(2, 1)) -
         a.at(0, 1) * (a.at(1, 0) * a.at(2, 2) - a.at(1, 2) * a.at(2, 0)) +
         a.at(0, 2) * (a.at(1, 0) * a.at(2, 1) - a.at(1, 1) * a.at(2, 0));
}

// The cofactor matrix of the upper 3x3, det * inverse transpose: it maps normals as the inverse
// transpose does, up to scale, and still works for a singular matrix.
std::array<double, 9> normalMatrix(const Matrix& a) {
  auto cofactor = [&](int r, int c) {
    const int r0 = r == 0 ? 1 : 0, r1 = r == 2 ? 1 : 2;
    const int c0 = c == 0 ? 1 : 0, c1 = c == 2 ? 1 : 2;
    const double minor = a.at(r0, c0) * a.at(r1, c1) - a.at(r0, c1) * a.at(r1, c0);
    return ((r + c) % 2 == 0) ? minor : -minor;
  };
  // A mirroring matrix has a negative determinant: the sign keeps normals pointing outward.
  const double sign = determinant3(a) < 0 ? -1.0 : 1.0;
  std::array<double, 9> n{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) n[static_cast<size_t>(c * 3 + r)] = sign * cofactor(r, c);
  return n;
}

float toFloat(double value) {
  // Beyond float's range becomes infinite rather than undefined.
  if (std::isnan(value)) return std::numeric_limits<float>::quiet_NaN();
  constexpr double kMax = std::numeric_limits<float>::max();
  if (value > kMax) return std::numeric_limits<float>::infinity();
  if (value < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

float3 transformPoint(const Matrix& a, float3 p) {
  double out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = a.at(r, 0) * p.x + a.at(r, 1) * p.y + a.at(r, 2) * p.z + a.at(r, 3);
  return {toFloat(out[0]), toFloat(out[1]), toFloat(out[2])};
}

float3 transformNormal(const std::array<double, 9>& n, float3 v) {
  double out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = n[static_cast<size_t>(r)] * v.x + n[static_cast<size_t>(3 + r)] * v.y +
             n[static_cast<size_t>(6 + r)] * v.z;
  const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  if (!(len > 0) || !std::isfinite(len)) return {0, 0, 0};
  return {toFloat(out[0] / len), toFloat(out[1] / len), toFloat(out[2] / len)};
}

// ---- Accessors ----

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

// Typed, checked reads from one accessor. Built only after its range has been checked against
// the buffer, so every read is inside it.
struct ElementReader {
  const uint8_t* data = nullptr;  // element 0
  size_t stride = 0;
  size_t count = 0;
  int components = 0;
  int component_type = 0;
  bool normalized = false;

  double raw(size_t element, int c) const {
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
  float component(size_t element, int c) const { return toFloat(raw(element, c)); }
  uint32_t index(size_t element) const {
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
};

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

// ---- The flattening ----

class Flattener {
 public:
  Flattener(const tinygltf::Model& gltf, std::string name, fs::path folder, uintmax_t source_bytes,
            Model& model)
      : gltf_(gltf),
        name_(std::move(name)),
        folder_(std::move(folder)),
        // Accessors without a buffer view are all zeros (before sparse values): their size is
        // not backed by the file, so it is bounded by it.
        implied_bytes_left_(16 * source_bytes + (uintmax_t{1} << 20)),
        model_(model) {}

  Expected<void> run() {
    if (Expected<void> ok = checkExtensions(); !ok) return ok;
    Expected<std::vector<int>> roots = sceneRoots();
    if (!roots) return roots.error();
    if (Expected<void> ok = checkNodeTree(); !ok) return ok;

    // Depth-first, a node's own mesh before its children, without recursion (a hierarchy may be
    // as deep as the file is long): the path from the root is the only state, one entry per
    // level with that node's global matrix and its next child.
    struct Level {
      size_t node;
      size_t next_child;
      Matrix global;
    };
    std::vector<Level> path;
    std::vector<char> drawn(gltf_.nodes.size(), 0);
    auto enter = [&](size_t index, const Matrix& parent) -> Expected<void> {
      if (drawn[index]) {
        warn("node " + std::to_string(index) +
             " is reached more than once from the scene's roots; it is drawn once");
        return {};
      }
      drawn[index] = 1;
      const tinygltf::Node& node = gltf_.nodes[index];
      Matrix global = parent * localMatrix(node, index);
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= gltf_.meshes.size())
          return makeError(name_ + ": node " + std::to_string(index) + " refers to mesh " +
                           std::to_string(node.mesh) + ", but the file has " +
                           std::to_string(gltf_.meshes.size()) + " meshes");
        if (node.skin >= 0)
          warn("skins are not applied: skinned meshes are drawn in their bind pose");
        if (Expected<void> ok = drawMesh(static_cast<size_t>(node.mesh), global); !ok) return ok;
      }
      path.push_back({index, 0, global});
      return {};
    };
    for (int root : *roots) {
      if (Expected<void> ok = enter(static_cast<size_t>(root), Matrix{}); !ok) return ok;
      while (!path.empty()) {
        Level& level = path.back();
        const std::vector<int>& children = gltf_.nodes[level.node].children;
        if (level.next_child == children.size()) {
          path.pop_back();
          continue;
        }
        const auto child = static_cast<size_t>(children[level.next_child++]);
        // `level` is not used past this point: entering a child may move the path.
        const Matrix parent = level.global;
        if (Expected<void> ok = enter(child, parent); !ok) return ok;
      }
    }
    return finish();
  }

 private:
  // ---- Warnings ----

  // A warning about the model file; at most kMaxWarnings distinct ones are listed.
  void warn(const std::string& text) { warnAbout(name_ + ": " + text); }
  // A warning that names its own file (a texture's).
  void warnAbout(const std::string& text) {
    if (!warned_.insert(text).second) return;
    if (warned_.size() > kMaxWarnings) {
      ++unlisted_warnings_;
      return;
    }
    model_.warnings.push_back(text);
  }

  // ---- Extensions, scene, node tree ----

  Expected<void> checkExtensions() {
    for (const std::string& extension : gltf_.extensionsRequired) {
      if (extension == "KHR_mesh_quantization") continue;  // read like any other accessor
      if (extension == "KHR_texture_transform" || extension.starts_with("KHR_materials_")) {
        warn("extension " + extension + " is not applied");
        continue;
      }
      return makeError(name_ + ": the file requires the extension " + extension +
                       ", which tessera does not support");
    }
    return {};
  }

  Expected<std::vector<int>> sceneRoots() {
    const size_t node_count = gltf_.nodes.size();
    int scene = gltf_.defaultScene;
    if (scene >= 0 && static_cast<size_t>(scene) >= gltf_.scenes.size()) {
      warn("the default scene " + std::to_string(scene) + " does not exist; scene 0 is drawn");
      scene = -1;
    }
    if (scene < 0 && !gltf_.scenes.empty()) scene = 0;
    std::vector<int> roots;
    if (scene >= 0) {
      for (int root : gltf_.scenes[static_cast<size_t>(scene)].nodes) {
        if (root < 0 || static_cast<size_t>(root) >= node_count)
          return makeError(name_ + ": scene " + std::to_string(scene) + " lists node " +
                           std::to_string(root) + ", but the file has " +
                           std::to_string(node_count) + " nodes");
        roots.push_back(root);
      }
      return roots;
    }
    // No scenes: every node that is no other node's child.
    std::vector<char> is_child(node_count, 0);
    for (const tinygltf::Node& node : gltf_.nodes)
      for (int child : node.children)
        if (child >= 0 && static_cast<size_t>(child) < node_count)
          is_child[static_cast<size_t>(child)] = 1;
    for (size_t n = 0; n < node_count; ++n)
      if (!is_child[n]) roots.push_back(static_cast<int>(n));
    return roots;
  }

  // glTF nodes form trees: child indices in range, no node its own ancestor, at most one
  // parent each. Cycles first (a depth-first search over the child links, iterative and linear),
  // since a cycle reached from elsewhere also gives one of its nodes a second parent.
  Expected<void> checkNodeTree() {
    const size_t node_count = gltf_.nodes.size();
    for (size_t n = 0; n < node_count; ++n) {
      for (int child : gltf_.nodes[n].children) {
        if (child < 0 || static_cast<size_t>(child) >= node_count)
          return makeError(name_ + ": node " + std::to_string(n) + " lists child " +
                           std::to_string(child) + ", but the file has " +
                           std::to_string(node_count) + " nodes");
        if (static_cast<size_t>(child) == n)
          return makeError(name_ + ": node " + std::to_string(n) +
                           " is its own child (the node graph must be a tree)");
      }
    }
    enum : char { kUnseen, kOnPath, kDone };
    std::vector<char> state(node_count, kUnseen);
    std::vector<std::pair<size_t, size_t>> path;  // node, next child to visit
    for (size_t start = 0; start < node_count; ++start) {
      if (state[start] != kUnseen) continue;
      state[start] = kOnPath;
      path.push_back({start, 0});
      while (!path.empty()) {
        auto& [node, next] = path.back();
        const std::vector<int>& children = gltf_.nodes[node].children;
        if (next == children.size()) {
          state[node] = kDone;
          path.pop_back();
          continue;
        }
        const auto child = static_cast<size_t>(children[next++]);
        if (state[child] == kOnPath)
          return makeError(name_ + ": node " + std::to_string(child) +
                           " is its own ancestor (its children lead back to it); the node "
                           "graph must be a tree");
        if (state[child] == kUnseen) {
          state[child] = kOnPath;
          path.push_back({child, 0});
        }
      }
    }
    constexpr int kNoParent = -1;
    std::vector<int> parent(node_count, kNoParent);
    for (size_t n = 0; n < node_count; ++n) {
      for (int child : gltf_.nodes[n].children) {
        const auto c = static_cast<size_t>(child);
        if (parent[c] != kNoParent)
          return makeError(name_ + ": node " + std::to_string(c) + " is a child of node " +
                           std::to_string(parent[c]) + " and of node " + std::to_string(n) +
                           " (glTF nodes have at most one parent)");
        parent[c] = static_cast<int>(n);
      }
    }
    return {};
  }

  Matrix localMatrix(const tinygltf::Node& node, size_t index) {
    Matrix local;
    if (node.matrix.size() == 16) {
      std::copy(node.matrix.begin(), node.matrix.end(), local.m.begin());
      return local;
    }
    if (!node.matrix.empty())
      warn("node " + std::to_string(index) + ": a matrix of " + std::to_string(node.matrix.size()) +
           " numbers (16 expected) is ignored");
    Matrix t, r, s;
    if (node.translation.size() == 3) {
      for (int i = 0; i < 3; ++i) t.at(i, 3) = node.translation[static_cast<size_t>(i)];
    } else if (!node.translation.empty()) {
      warn("node " + std::to_string(index) + ": a translation that is not 3 numbers is ignored");
    }
    if (node.rotation.size() == 4) {
      double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
      const double len = std::sqrt(x * x + y * y + z * z + w * w);
      if (len > 0 && std::isfinite(len)) {
        x /= len, y /= len, z /= len, w /= len;
        r.at(0, 0) = 1 - 2 * (y * y + z * z);
        r.at(1, 0) = 2 * (x * y + w * z);
        r.at(2, 0) = 2 * (x * z - w * y);
        r.at(0, 1) = 2 * (x * y - w * z);
        r.at(1, 1) = 1 - 2 * (x * x + z * z);
        r.at(2, 1) = 2 * (y * z + w * x);
        r.at(0, 2) = 2 * (x * z + w * y);
        r.at(1, 2) = 2 * (y * z - w * x);
        r.at(2, 2) = 1 - 2 * (x * x + y * y);
      } else {
        warn("node " + std::to_string(index) + ": a zero or non-finite rotation is ignored");
      }
    } else if (!node.rotation.empty()) {
      warn("node " + std::to_string(index) + ": a rotation that is not 4 numbers is ignored");
    }
    if (node.scale.size() == 3) {
      for (int i = 0; i < 3; ++i) s.at(i, i) = node.scale[static_cast<size_t>(i)];
    } else if (!node.scale.empty()) {
      warn("node " + std::to_string(index) + ": a scale that is not 3 numbers is ignored");
    }
    return t * r * s;  // glTF: T * R * S
  }

  // ---- Accessors ----

  std::string accessorName(int accessor, const std::string& role) const {
    return name_ + ": accessor " + std::to_string(accessor) + " (" + role + ")";
  }

  // The checked byte range of a buffer view, or why it has none.
  Expected<std::span<const uint8_t>> viewBytes(int view_index, const std::string& what) const {
    if (view_index < 0 || static_cast<size_t>(view_index) >= gltf_.bufferViews.size())
      return makeError(what + " refers to bufferView " + std::to_string(view_index) +
                       ", but the file has " + std::to_string(gltf_.bufferViews.size()));
    const tinygltf::BufferView& view = gltf_.bufferViews[static_cast<size_t>(view_index)];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= gltf_.buffers.size())
      return makeError(what + ": bufferView " + std::to_string(view_index) + " refers to buffer " +
                       std::to_string(view.buffer) + ", but the file has " +
                       std::to_string(gltf_.buffers.size()));
    const std::vector<unsigned char>& data = gltf_.buffers[static_cast<size_t>(view.buffer)].data;
    if (!fits(view.byteOffset, 1, 1, view.byteLength, data.size()))
      return makeError(what + ": bufferView " + std::to_string(view_index) + " (bytes " +
                       std::to_string(view.byteOffset) + " to " +
                       std::to_string(uint64_t{view.byteOffset} + view.byteLength) +
                       ") lies outside buffer " + std::to_string(view.buffer) + " (" +
                       std::to_string(data.size()) + " bytes)");
    return std::span<const uint8_t>(data.data() + view.byteOffset, view.byteLength);
  }

  // A reader for `accessor`, its type and component types checked against `allowed_types` and
  // `allowed_components` (empty: any), and its range against its buffer view.
  Expected<ElementReader> reader(int accessor_index, const std::string& role,
                                 std::initializer_list<int> allowed_types,
                                 std::initializer_list<int> allowed_components) {
    if (accessor_index < 0 || static_cast<size_t>(accessor_index) >= gltf_.accessors.size())
      return makeError(name_ + ": " + role + " refers to accessor " +
                       std::to_string(accessor_index) + ", but the file has " +
                       std::to_string(gltf_.accessors.size()));
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

    if (!accessor.sparse.isSparse && accessor.bufferView >= 0) {
      Expected<std::span<const uint8_t>> bytes = viewBytes(accessor.bufferView, what);
      if (!bytes) return bytes.error();
      const tinygltf::BufferView& view =
          gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
      reader.stride = view.byteStride != 0 ? view.byteStride : element;
      if (reader.stride < element)
        return makeError(what + ": bufferView " + std::to_string(accessor.bufferView) +
                         " has byteStride " + std::to_string(view.byteStride) +
                         ", smaller than the " + std::to_string(element) + "-byte element");
      if (!fits(accessor.byteOffset, reader.count, reader.stride, element, bytes->size()))
        return makeError(
            what + ": " + std::to_string(reader.count) + " elements of " + std::to_string(element) +
            " bytes, " + std::to_string(reader.stride) + " apart from byte " +
            std::to_string(accessor.byteOffset) + ", reach past the end of bufferView " +
            std::to_string(accessor.bufferView) + " (" + std::to_string(bytes->size()) + " bytes)");
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

  Expected<std::vector<uint8_t>> densify(const tinygltf::Accessor& accessor,
                                         const std::string& what, size_t element) {
    const size_t count = accessor.count;
    std::vector<uint8_t> dense;
    if (accessor.bufferView >= 0) {
      Expected<std::span<const uint8_t>> bytes = viewBytes(accessor.bufferView, what);
      if (!bytes) return bytes.error();
      const tinygltf::BufferView& view =
          gltf_.bufferViews[static_cast<size_t>(accessor.bufferView)];
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
    Expected<std::span<const uint8_t>> indices = viewBytes(sparse.indices.bufferView, sparse_what);
    if (!indices) return indices.error();
    Expected<std::span<const uint8_t>> values = viewBytes(sparse.values.bufferView, sparse_what);
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
  std::optional<ElementReader> optionalAttribute(const tinygltf::Primitive& primitive,
                                                 const std::string& semantic,
                                                 const std::string& where, size_t vertex_count,
                                                 std::initializer_list<int> types,
                                                 std::initializer_list<int> components,
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

  // ---- Materials and textures ----

  // The model material for a glTF material index (-1: none), added on first use.
  Expected<uint16_t> materialFor(int gltf_material) {
    if (gltf_material >= 0 && static_cast<size_t>(gltf_material) >= gltf_.materials.size()) {
      warn("a primitive refers to material " + std::to_string(gltf_material) +
           ", which does not exist; the default material is used");
      gltf_material = -1;
    }
    auto found = material_index_.find(gltf_material);
    if (found != material_index_.end()) return found->second;
    if (model_.materials.size() == kMaxMaterials)
      return makeError(name_ + ": more than " + std::to_string(kMaxMaterials) +
                       " materials in use");
    const auto index = static_cast<uint16_t>(model_.materials.size());
    model_.materials.push_back(
        gltf_material < 0 ? Material{} : buildMaterial(static_cast<size_t>(gltf_material)));
    material_index_.emplace(gltf_material, index);
    return index;
  }

  Material buildMaterial(size_t index) {
    const tinygltf::Material& source = gltf_.materials[index];
    const std::string label =
        "material " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
    Material material;
    material.double_sided = source.doubleSided;
    const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
    material.base_color = float4{1, 1, 1, 1};
    if (factor.size() == 4) {
      for (int i = 0; i < 4; ++i) {
        const double value = factor[static_cast<size_t>(i)];
        material.base_color[i] = std::isfinite(value) ? toFloat(std::clamp(value, 0.0, 1.0)) : 1.0f;
      }
    } else {
      warn(label + ": a baseColorFactor that is not 4 numbers is ignored");
    }
    const tinygltf::TextureInfo& info = source.pbrMetallicRoughness.baseColorTexture;
    if (info.index >= 0) {
      const std::string dropped = "; " + label + " is drawn without its texture";
      if (static_cast<size_t>(info.index) >= gltf_.textures.size()) {
        warn(label + " uses texture " + std::to_string(info.index) + ", which does not exist" +
             dropped);
        return material;
      }
      const tinygltf::Texture& texture = gltf_.textures[static_cast<size_t>(info.index)];
      if (texture.source < 0 || static_cast<size_t>(texture.source) >= gltf_.images.size()) {
        warn("texture " + std::to_string(info.index) + " has no usable image" + dropped);
        return material;
      }
      material.albedo = image(static_cast<size_t>(texture.source), dropped);
      if (texture.sampler >= 0 && static_cast<size_t>(texture.sampler) < gltf_.samplers.size())
        material.sampler = sampler(static_cast<size_t>(texture.sampler));
      else if (texture.sampler >= 0)
        warn("texture " + std::to_string(info.index) + " refers to sampler " +
             std::to_string(texture.sampler) + ", which does not exist; the default is used");
    }
    return material;
  }

  Sampler sampler(size_t index) {
    const tinygltf::Sampler& source = gltf_.samplers[index];
    Sampler sampler;
    // tessera samples without mipmaps: the magnification filter says nearest or linear; without
    // one, the minification filter's base does.
    int filter = source.magFilter;
    if (filter < 0 && source.minFilter >= 0)
      filter = (source.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
                source.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                source.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR)
                   ? TINYGLTF_TEXTURE_FILTER_NEAREST
                   : TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.filter = filter == TINYGLTF_TEXTURE_FILTER_NEAREST ? TextureFilter::kNearest
                                                               : TextureFilter::kBilinear;
    auto wrap = [&](int mode) {
      if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClamp;
      if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
        warn("sampler " + std::to_string(index) + ": MIRRORED_REPEAT is drawn as REPEAT");
      return TextureWrap::kRepeat;
    };
    const TextureWrap s = wrap(source.wrapS), t = wrap(source.wrapT);
    if (s != t)
      warn("sampler " + std::to_string(index) +
           ": different wrap modes along s and t; tessera uses one, s's");
    sampler.wrap = s;
    return sampler;
  }

  std::shared_ptr<const Texture> image(size_t index, const std::string& dropped) {
    auto cached = images_.find(index);
    if (cached != images_.end()) return cached->second;
    std::shared_ptr<const Texture>& slot = images_[index];
    const tinygltf::Image& source = gltf_.images[index];
    const std::string label = name_ + " image " + std::to_string(index);
    Expected<Texture> decoded = makeError(label + ": no image data");
    if (source.bufferView >= 0) {
      Expected<std::span<const uint8_t>> bytes = viewBytes(source.bufferView, label);
      if (!bytes) {
        warn(bytes.error().message.substr(name_.size() + 1) + dropped);
        return nullptr;
      }
      decoded = decodeTexture(bytes->data(), bytes->size(), label, /*srgb=*/true);
    } else if (!source.image.empty()) {
      decoded = decodeTexture(source.image.data(), source.image.size(), label, /*srgb=*/true);
    } else if (!source.uri.empty()) {
      const std::string reference = percentDecoded(source.uri);
      if (folder_.empty()) {
        warn("image " + std::to_string(index) + ": '" + reference +
             "' is an external file, and this model was given in memory" + dropped);
        return nullptr;
      }
      Expected<fs::path> path = resolveReferencedFile(folder_, reference);
      if (!path) {
        warn("image " + std::to_string(index) + ": '" + reference +
             "' refused: " + path.error().message + dropped);
        return nullptr;
      }
      std::error_code error;
      if (!fs::is_regular_file(*path, error)) {
        warnAbout(path->string() + ": texture not found" + dropped);
        return nullptr;
      }
      decoded = loadTexture(*path, /*srgb=*/true);
    }
    if (!decoded) {
      warnAbout(decoded.error().message + dropped);
      return nullptr;
    }
    if (decoded->texels.size() > kMaxTotalTexels - total_texels_) {
      warn("image " + std::to_string(index) + " skipped: the model's textures exceed " +
           std::to_string(kMaxTotalTexels) + " texels in all" + dropped);
      return nullptr;
    }
    total_texels_ += decoded->texels.size();
    slot = std::make_shared<const Texture>(std::move(decoded).value());
    return slot;
  }

  // ---- Meshes ----

  Expected<void> drawMesh(size_t mesh_index, const Matrix& global) {
    const tinygltf::Mesh& mesh = gltf_.meshes[mesh_index];
    const bool mirrored = determinant3(global) < 0;
    const std::array<double, 9> normal_matrix = normalMatrix(global);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where =
          "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
      Expected<void> ok = drawPrimitive(mesh.primitives[p], where, global, normal_matrix, mirrored);
      if (!ok) return ok;
    }
    return {};
  }

  Expected<void> drawPrimitive(const tinygltf::Primitive& primitive, const std::string& where,
                               const Matrix& global, const std::array<double, 9>& normal_matrix,
                               bool mirrored) {
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      ++skipped_by_mode_[mode];
      return {};
    }
    if (!primitive.targets.empty()) warn("morph targets are not applied");
    auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end()) {
      warn(where + " has no POSITION and is skipped");
      return {};
    }
    // KHR_mesh_quantization allows integer positions, normals and texture coordinates.
    Expected<ElementReader> positions =
        reader(position_it->second, "POSITION of " + where, {3}, {});
    if (!positions) return positions.error();
    const size_t vertex_count = positions->count;

    std::optional<ElementReader> indices;
    size_t corner_count = vertex_count;
    if (primitive.indices >= 0) {
      Expected<ElementReader> read =
          reader(primitive.indices, "indices of " + where, {1},
                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      if (!read) return read.error();
      indices = *read;
      corner_count = indices->count;
    }
    size_t triangle_count = 0;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      triangle_count = corner_count / 3;
      if (corner_count % 3 != 0)
        warn(where + ": " + std::to_string(corner_count % 3) +
             " indices after the last whole triangle are ignored");
    } else if (corner_count >= 3) {
      triangle_count = corner_count - 2;
    }
    if (triangle_count == 0) {
      warn(where + " has fewer than 3 vertices and is skipped");
      return {};
    }
    Mesh& out = model_.mesh;
    const size_t new_vertices = std::min(vertex_count, 3 * triangle_count);
    if (triangle_count > kMaxTriangles - out.triangleCount() ||
        new_vertices > kMaxVertices - out.vertexCount())
      return makeError(name_ + ": the scene flattens to more than " +
                       std::to_string(kMaxTriangles) + " triangles or vertices; refused");

    Expected<void> fatal;
    const std::optional<ElementReader> normals =
        optionalAttribute(primitive, "NORMAL", where, vertex_count, {3}, {}, fatal);
    if (!fatal) return fatal;
    Expected<uint16_t> material = materialFor(primitive.material);
    if (!material) return material.error();
    int uv_set = 0;
    if (primitive.material >= 0 &&
        static_cast<size_t>(primitive.material) < gltf_.materials.size()) {
      const tinygltf::TextureInfo& info = gltf_.materials[static_cast<size_t>(primitive.material)]
                                              .pbrMetallicRoughness.baseColorTexture;
      if (info.index >= 0) uv_set = std::max(info.texCoord, 0);
    }
    const std::optional<ElementReader> uvs = optionalAttribute(
        primitive, "TEXCOORD_" + std::to_string(uv_set), where, vertex_count, {2}, {}, fatal);
    if (!fatal) return fatal;
    if (!uvs && model_.materials[*material].albedo)
      warn(where + ": its material has a texture but the primitive has no TEXCOORD_" +
           std::to_string(uv_set));
    const std::optional<ElementReader> colors =
        optionalAttribute(primitive, "COLOR_0", where, vertex_count, {3, 4},
                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                          fatal);
    if (!fatal) return fatal;

    // Each vertex of this primitive is emitted once, on first use. The remap is stamped per
    // primitive so it never needs clearing.
    if (remap_stamp_.size() < vertex_count) {
      remap_stamp_.resize(vertex_count, 0);
      remap_vertex_.resize(vertex_count, 0);
    }
    ++stamp_;
    const size_t first_vertex = out.positions.size();
    if (uvs) out.uvs.resize(first_vertex, float2{0, 0});
    if (colors) out.colors.resize(first_vertex, float4{1, 1, 1, 1});
    bool normals_usable = normals.has_value();

    auto vertexOf = [&](size_t corner) -> Expected<uint32_t> {
      const size_t local = indices ? indices->index(corner) : corner;
      if (local >= vertex_count)
        return makeError(name_ + ": " + where + ": index " + std::to_string(local) +
                         " is past the " + std::to_string(vertex_count) + " vertices");
      if (remap_stamp_[local] == stamp_) return remap_vertex_[local];
      const auto vertex = static_cast<uint32_t>(out.positions.size());
      remap_stamp_[local] = stamp_;
      remap_vertex_[local] = vertex;
      out.positions.push_back(
          transformPoint(global, {positions->component(local, 0), positions->component(local, 1),
                                  positions->component(local, 2)}));
      float3 normal{0, 0, 0};
      if (normals) {
        normal = transformNormal(normal_matrix,
                                 {normals->component(local, 0), normals->component(local, 1),
                                  normals->component(local, 2)});
        normals_usable &= normal.x != 0 || normal.y != 0 || normal.z != 0;
      }
      out.normals.push_back(normal);
      if (uvs)  // glTF's v = 0 is the top of the image; tessera's is the bottom.
        out.uvs.push_back({uvs->component(local, 0), 1.0f - uvs->component(local, 1)});
      if (colors)
        out.colors.push_back({colors->component(local, 0), colors->component(local, 1),
                              colors->component(local, 2),
                              colors->components == 4 ? colors->component(local, 3) : 1.0f});
      return vertex;
    };

    for (size_t t = 0; t < triangle_count; ++t) {
      size_t corners[3];
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        corners[0] = 3 * t, corners[1] = 3 * t + 1, corners[2] = 3 * t + 2;
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle is listed clockwise; swap to keep one winding (glTF 3.7.2.1).
        corners[0] = t;
        corners[1] = t + 1 + t % 2;
        corners[2] = t + 2 - t % 2;
      } else {
        corners[0] = 0, corners[1] = t + 1, corners[2] = t + 2;
      }
      // A mirroring transform turns counter-clockwise into clockwise: undo it.
      if (mirrored) std::swap(corners[1], corners[2]);
      bool finite = true;
      for (size_t corner : corners) {
        Expected<uint32_t> vertex = vertexOf(corner);
        if (!vertex) return vertex.error();
        out.indices.push_back(*vertex);
        finite &= isFinite(out.positions[*vertex]);
      }
      out.triangle_materials.push_back(*material);
      if (!finite) ++model_.nonfinite_triangles;
    }
    if (uvs) out.uvs.resize(out.positions.size(), float2{0, 0});
    if (colors) out.colors.resize(out.positions.size(), float4{1, 1, 1, 1});
    if (!normals_usable) {
      if (normals)
        warn(where + ": some normals are zero or not finite; smooth normals are generated");
      generated_normal_ranges_.push_back({first_vertex, out.positions.size()});
    }
    return {};
  }

  Expected<void> finish() {
    Mesh& mesh = model_.mesh;
    if (mesh.triangleCount() == 0) {
      std::string why = "no triangles in the scene";
      if (!skipped_by_mode_.empty()) why += " (only points or lines, which are not drawn)";
      return makeError(name_ + ": " + why);
    }
    // Vertices of different primitives are never shared, so smooth normals over the whole mesh
    // equal each primitive's own; they are copied only where the file gave none.
    if (!generated_normal_ranges_.empty()) {
      Mesh shape;
      shape.positions = mesh.positions;
      shape.indices = mesh.indices;
      generateSmoothNormals(shape);
      for (auto [begin, end] : generated_normal_ranges_)
        std::copy(shape.normals.begin() + static_cast<std::ptrdiff_t>(begin),
                  shape.normals.begin() + static_cast<std::ptrdiff_t>(end),
                  mesh.normals.begin() + static_cast<std::ptrdiff_t>(begin));
    }
    if (!mesh.uvs.empty()) mesh.uvs.resize(mesh.positions.size(), float2{0, 0});
    if (!mesh.colors.empty()) mesh.colors.resize(mesh.positions.size(), float4{1, 1, 1, 1});

    static constexpr const char* kModeNames[] = {"points", "lines", "line loops", "line strips"};
    for (auto [mode, count] : skipped_by_mode_) {
      const std::string what =
          mode >= 0 && mode < 4 ? kModeNames[mode] : "primitives of mode " + std::to_string(mode);
      warn(std::to_string(count) + " primitive(s) of " + what +
           " skipped: only triangles are drawn");
    }
    size_t double_sided = 0;
    for (const Material& material : model_.materials) double_sided += material.double_sided;
    model_.cull_back_faces = double_sided == 0;
    if (double_sided > 0 && double_sided < model_.materials.size())
      warn("some materials are double-sided and some are not; back faces are drawn for all");
    if (model_.nonfinite_triangles > 0)
      model_.warnings.push_back(
          name_ + ": " + std::to_string(model_.nonfinite_triangles) +
          " triangles have a NaN or infinite vertex position (kept so triangle ids stay in load "
          "order; they are not drawn)");
    if (unlisted_warnings_ > 0)
      model_.warnings.push_back(name_ + ": " + std::to_string(unlisted_warnings_) +
                                " more warnings like these");
    return {};
  }

  const tinygltf::Model& gltf_;
  const std::string name_;
  const fs::path folder_;
  uintmax_t implied_bytes_left_;
  Model& model_;

  std::map<int, std::vector<uint8_t>> dense_;  // sparse or bufferView-less accessors
  std::map<int, uint16_t> material_index_;
  std::map<size_t, std::shared_ptr<const Texture>> images_;
  size_t total_texels_ = 0;
  std::vector<uint32_t> remap_stamp_, remap_vertex_;
  uint32_t stamp_ = 0;
  std::vector<std::pair<size_t, size_t>> generated_normal_ranges_;
  std::map<int, size_t> skipped_by_mode_;
  std::set<std::string> warned_;
  size_t unlisted_warnings_ = 0;
};

// tinygltf's messages are lines ending in '\n'; this joins the first few into one.
std::string joinedLines(const std::string& text) {
  constexpr size_t kMaxLines = 5;
  std::string out;
  size_t lines = 0, begin = 0;
  while (begin < text.size()) {
    size_t end = std::min(text.find('\n', begin), text.size());
    std::string line = trimmed(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    if (line.empty()) continue;
    if (++lines > kMaxLines) continue;
    if (!out.empty()) out += "; ";
    out += line;
  }
  if (lines > kMaxLines) out += "; and " + std::to_string(lines - kMaxLines) + " more";
  return out;
}

Expected<Model> parseGltf(std::span<const uint8_t> bytes, const std::string& name,
                          const fs::path& folder) {
  if (bytes.empty()) return makeError(name + ": the file is empty: no triangles");
  if (bytes.size() > kMaxGltfBytes)
    return makeError(name + ": the file is " + std::to_string(bytes.size()) +
                     " bytes; glTF files over 2 GiB are refused");
  const bool binary = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  std::string_view json_text;
  if (binary) {
    if (Expected<void> ok = checkGlbContainer(bytes, name); !ok) return ok.error();
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()) + 20,
                                 readU32(bytes.data() + 12));
  } else {
    json_text = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  if (Expected<void> ok = checkJsonShape(json_text, name); !ok) return ok.error();

  ExternalFiles files{folder, name, {}, 0};
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &refuseWrite, &files});
  parser.SetImageLoader(&keepEncodedImage, nullptr);
  tinygltf::Model gltf;
  std::string errors, library_warnings;
  const std::string base(kFolderMarker.substr(0, kFolderMarker.size() - 1));
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&gltf, &errors, &library_warnings, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), base)
             : parser.LoadASCIIFromString(&gltf, &errors, &library_warnings, json_text.data(),
                                          static_cast<unsigned int>(json_text.size()), base);
  if (!parsed) {
    if (!files.refusals.empty())
      return makeError(name + ": a buffer file cannot be read: " + files.refusals.front());
    std::string message = joinedLines(errors);
    return makeError(name + ": not a readable glTF file: " +
                     (message.empty() ? "tinygltf gave no reason" : message));
  }

  Model model;
  Flattener flattener(gltf, name, folder, bytes.size() + files.bytes_read, model);
  if (Expected<void> ok = flattener.run(); !ok) return ok.error();
  std::string passed_on = joinedLines(library_warnings);
  if (!passed_on.empty()) model.warnings.insert(model.warnings.begin(), name + ": " + passed_on);
  return model;
}

template <typename Load>
Expected<Model> guarded(const std::string& name, Load load) {
  try {
    return load();
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::length_error&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::exception& error) {
    // tinygltf and nlohmann::json throw on some malformed input (a zero-length GLB buffer).
    return makeError(name + ": not a readable glTF file: " + error.what());
  }
}

}  // namespace

Expected<Model> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                   const std::filesystem::path& folder) {
  return guarded(name, [&] { return parseGltf(bytes, name, folder); });
}

Expected<Model> loadGltf(const std::filesystem::path& path) {
  const std::string name = path.string();
  return guarded(name, [&]() -> Expected<Model> {
    Expected<std::vector<unsigned char>> bytes = readModelFile(path, kMaxGltfBytes, "glTF");
    if (!bytes) return bytes.error();
    fs::path folder = path.parent_path();
    if (folder.empty()) folder = ".";
    return parseGltf(*bytes, name, folder);
  });
}

}  // namespace tessera::io
