#include "gltf_container.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model_paths.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

using Json = nlohmann::json;

// JSON shape: far beyond real files, far below what tinygltf's recursion and memory can take.
constexpr int kMaxJsonDepth = 64;
constexpr size_t kMaxJsonContainers = size_t{1} << 22;
// tinygltf turns each JSON object into a struct of its own, up to 2 KiB (a material) for as
// little as 3 bytes of text ("{},"). Files whose objects would take more than this are refused;
// a large real scene takes a few hundred MiB at most.
constexpr uint64_t kMaxParsedBytes = uint64_t{1} << 30;

constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

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

// Where the JSON scan is ("meshes[0].primitives[1].indices"), and the range check of the
// integers tinygltf reads into an int: it truncates them, so 2^32 would become 0 and 2^31 a
// negative count. Every glTF index, count, offset and enum is checked wherever it appears, except
// in extras and extensions, which tessera does not read.
class JsonPath {
 public:
  // `depth` is the parser's: the number of containers the event is inside (0 for the root's
  // start and end). It keeps the path right also where the parser reports no end (the end of a
  // container it discards, see checkJsonShape).
  void follow(int depth, Json::parse_event_t event, const Json& parsed) {
    if (depth >= 0 && static_cast<size_t>(depth) < levels_.size())
      levels_.resize(static_cast<size_t>(depth));
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        levels_.push_back({event == Json::parse_event_t::array_start, 0, elementName(), ""});
        break;
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        break;
      case Json::parse_event_t::key:
        if (!levels_.empty()) levels_.back().key = parsed.get<std::string>();
        break;
      case Json::parse_event_t::value:
        checkValue(parsed);
        break;
    }
  }

 private:
  struct Level {
    bool array;
    size_t next_index;
    std::string name;  // this container's own key or index: "primitives", "[1]"
    std::string key;   // in an object, the key being read
  };

  // The key or index of the element about to be read, advancing an array's index.
  std::string elementName() {
    if (levels_.empty()) return "";
    Level& level = levels_.back();
    if (!level.array) return level.key;
    // Appended, not "[" + ...: GCC 12 warns falsely (-Wrestrict) about the operator+ form.
    std::string index(1, '[');
    index += std::to_string(level.next_index++);
    index += ']';
    return index;
  }

  // Whether the element read now is one tinygltf reads into an int.
  bool isIntegerProperty(const std::string& element) const {
    static const std::set<std::string, std::less<>> kKeys = {
        "buffer",    "bufferView",    "byteOffset", "byteLength", "byteStride",
        "target",    "componentType", "count",      "mesh",       "skin",
        "camera",    "scene",         "indices",    "material",   "mode",
        "index",     "texCoord",      "source",     "sampler",    "magFilter",
        "minFilter", "wrapS",         "wrapT",      "skeleton",   "inverseBindMatrices",
        "input",     "output",        "node"};
    for (const Level& level : levels_)
      if (level.name == "extras" || level.name == "extensions") return false;
    const Level& here = levels_.back();
    if (here.array) return here.name == "nodes" || here.name == "children" || here.name == "joints";
    // Attribute and morph target objects map names to accessor indices.
    if (here.name == "attributes") return true;
    if (levels_.size() >= 2 && levels_[levels_.size() - 2].name == "targets") return true;
    return kKeys.contains(element);
  }

  void checkValue(const Json& value) {
    if (levels_.empty()) return;
    const std::string element = elementName();
    if (!value.is_number_integer() || !isIntegerProperty(element)) return;
    constexpr int64_t kMax = std::numeric_limits<int32_t>::max();
    constexpr int64_t kMin = std::numeric_limits<int32_t>::min();
    std::string shown, limit;
    if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t{kMax}) {
      shown = std::to_string(value.get<uint64_t>());
      limit = "at most " + std::to_string(kMax);
    } else if (!value.is_number_unsigned() && value.get<int64_t>() < kMin) {
      shown = std::to_string(value.get<int64_t>());
      limit = "at least " + std::to_string(kMin);
    } else {
      return;
    }
    throw JsonShapeError{where(element) + " is " + shown + ", out of range (" + limit + ")"};
  }

  std::string where(const std::string& element) const {
    std::string text;
    for (size_t i = 1; i < levels_.size(); ++i) {
      const std::string& part = levels_[i].name;
      if (!text.empty() && !part.starts_with('[')) text += '.';
      text += part;
    }
    if (!text.empty() && !element.starts_with('[')) text += '.';
    return text + element;
  }

  std::vector<Level> levels_;
};

}  // namespace

uint32_t readU32(const uint8_t* p) {
  static_assert(std::endian::native == std::endian::little, "GLB is little-endian");
  uint32_t value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

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
  // tinygltf refuses less than 4 bytes, in words of its own.
  if (bin_length < 4)
    return makeError(name + ": corrupt GLB: the binary chunk holds " + std::to_string(bin_length) +
                     " bytes; a binary chunk holds at least 4");
  if (json_end + 8 + bin_length > length)
    return makeError(truncated + "the binary chunk claims " + std::to_string(bin_length) +
                     " bytes, " + std::to_string(length - json_end - 8) + " are left");
  return {};
}

namespace {

// The parser's callback for checkJsonShape: counts what the JSON would make and throws
// JsonShapeError past a limit; keeps (returns true for) only what the image check reads at depth
// 1 and 3, so that the parsed tree stays small.
class JsonShapeLimits {
 public:
  bool operator()(int depth, Json::parse_event_t event, Json& parsed) {
    path_.follow(depth, event, parsed);
    switch (event) {
      case Json::parse_event_t::object_start:
      case Json::parse_event_t::array_start:
        count(depth, event);
        return true;
      case Json::parse_event_t::key:
        if (depth == 1) {
          top_key_ = parsed.get<std::string>();
          return parsed == "images" || parsed == "bufferViews" || parsed == "buffers";
        }
        if (depth == 3)
          return parsed == "bufferView" || parsed == "buffer" || parsed == "byteOffset" ||
                 parsed == "byteLength";
        return true;
      default:
        return true;
    }
  }

 private:
  void count(int depth, Json::parse_event_t event) {
    if (depth >= kMaxJsonDepth)
      throw JsonShapeError{"the JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                           " levels"};
    if (++containers_ > kMaxJsonContainers)
      throw JsonShapeError{"the JSON has more than " + std::to_string(kMaxJsonContainers) +
                           " objects and arrays"};
    // The JSON value itself and tinygltf's copy of it (extras become tinygltf::Values).
    parsed_bytes_ += 256;
    if (event == Json::parse_event_t::object_start && depth == 2)
      parsed_bytes_ += structBytes(top_key_);
    // Objects in the arrays of those: primitives, animation channels and samplers.
    if (event == Json::parse_event_t::object_start && depth == 4)
      parsed_bytes_ += std::max(sizeof(tinygltf::Primitive), sizeof(tinygltf::AnimationChannel));
    if (parsed_bytes_ > kMaxParsedBytes)
      throw JsonShapeError{"the JSON describes more objects than tessera parses (over " +
                           std::to_string(kMaxParsedBytes >> 20) + " MiB of parser structures)"};
  }

  JsonPath path_;
  size_t containers_ = 0;
  uint64_t parsed_bytes_ = 0;
  std::string top_key_;  // the key at depth 1: what an object at depth 2 will become
};

// "[json.exception.parse_error.101] parse error at line 3, column 7: syntax error while parsing
// array - unexpected end of input; expected ']'" as "at line 3, column 7: unexpected end of
// input; expected ']'": where, and what was found.
std::string describeParseError(const Json::parse_error& error) {
  std::string what = error.what();
  std::string where = "at byte " + std::to_string(error.byte);
  size_t colon = what.find("] ");
  if (size_t at = what.find("at line "); at != std::string::npos) {
    colon = what.find(':', at);
    where = what.substr(at, colon - at);
  }
  std::string why = colon == std::string::npos ? what : what.substr(colon + 1);
  if (size_t dash = why.find(" - "); dash != std::string::npos) why = why.substr(dash + 3);
  return where + ": " + trimmed(why);
}

// An error where an image's bufferView lies outside its buffer (which tinygltf would read past);
// the other broken references are left to tinygltf, which refuses them itself.
Expected<void> checkImageViews(const Json& root, const std::string& name) {
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
      continue;
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

}  // namespace

Expected<void> checkJsonShape(std::string_view text, const std::string& name) {
  Json root;
  try {
    root = Json::parse(text.begin(), text.end(), JsonShapeLimits{}, /*allow_exceptions=*/true,
                       /*ignore_comments=*/false);
  } catch (const JsonShapeError& error) {
    return makeError(name + ": " + error.message);
  } catch (const Json::parse_error& error) {
    return makeError(name + ": not valid JSON " + describeParseError(error));
  }
  if (!root.is_object()) return makeError(name + ": the JSON is not an object: not glTF");
  return checkImageViews(root, name);
}

}  // namespace tessera::io::gltf
