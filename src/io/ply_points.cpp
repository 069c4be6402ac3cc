#include "ply_points.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>
#include <vector>

#include <tessera/scene/color.h>

namespace tessera::io {

namespace {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
  std::string_view name;
  int bytes = 0;  // of its type: 1, 2, 4 or 8
  bool is_float = false, is_signed = false;
};

// What the point reader needs of a header: the format, the vertex properties, the vertex count
// and where the body starts.
struct PlyVertexHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyProperty> properties;
  uint64_t count = 0;
  size_t body = 0;  // offset of the first byte after end_header's line
};

std::optional<PlyProperty> scalarType(std::string_view type) {
  struct Known {
    std::string_view name;
    int bytes;
    bool is_float, is_signed;
  };
  static constexpr Known kTypes[] = {
      {"char", 1, false, true},    {"int8", 1, false, true},    {"uchar", 1, false, false},
      {"uint8", 1, false, false},  {"short", 2, false, true},   {"int16", 2, false, true},
      {"ushort", 2, false, false}, {"uint16", 2, false, false}, {"int", 4, false, true},
      {"int32", 4, false, true},   {"uint", 4, false, false},   {"uint32", 4, false, false},
      {"float", 4, true, true},    {"float32", 4, true, true},  {"double", 8, true, true},
      {"float64", 8, true, true},
  };
  for (const Known& known : kTypes)
    if (known.name == type) return PlyProperty{{}, known.bytes, known.is_float, known.is_signed};
  return std::nullopt;
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// The header, when the file is a PLY of one `vertex` element of scalar properties.
std::optional<PlyVertexHeader> vertexOnlyHeader(std::string_view text) {
  PlyVertexHeader header;
  size_t at = 0, elements = 0;
  while (at < text.size()) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::vector<std::string_view> w = words(text.substr(at, end - at));
    at = end + 1;
    if (w.empty()) continue;
    if (w[0] == "end_header") {
      header.body = std::min(at, text.size());
      return elements == 1 ? std::optional(header) : std::nullopt;
    }
    if (w[0] == "format" && w.size() == 3) {
      if (w[1] == "binary_little_endian") header.format = PlyFormat::kBinaryLittleEndian;
      if (w[1] == "binary_big_endian") header.format = PlyFormat::kBinaryBigEndian;
    } else if (w[0] == "element" && w.size() == 3) {
      if (++elements > 1 || w[1] != "vertex") return std::nullopt;
      if (std::from_chars(w[2].data(), w[2].data() + w[2].size(), header.count).ec != std::errc{})
        return std::nullopt;
    } else if (w[0] == "property") {
      if (w.size() != 3) return std::nullopt;  // a list
      std::optional<PlyProperty> property = scalarType(w[1]);
      if (!property) return std::nullopt;
      property->name = w[2];
      header.properties.push_back(*property);
    }
  }
  return std::nullopt;
}

// Where x, y, z and the colour are among the properties; -1 for absent.
struct VertexLayout {
  std::array<int, 6> index{-1, -1, -1, -1, -1, -1};  // x y z red green blue
  bool colored() const { return index[3] >= 0 && index[4] >= 0 && index[5] >= 0; }
};

VertexLayout layoutOf(const std::vector<PlyProperty>& properties) {
  static constexpr std::string_view kNames[6] = {"x", "y", "z", "red", "green", "blue"};
  VertexLayout layout;
  for (size_t p = 0; p < properties.size(); ++p)
    for (int i = 0; i < 6; ++i)
      if (properties[p].name == kNames[i] && layout.index[i] < 0) layout.index[i] = int(p);
  return layout;
}

// A colour channel in 0..1: integers scaled by their type's maximum, floats as they are.
float unitChannel(double value, const PlyProperty& type) {
  if (!type.is_float)
    value /= type.is_signed ? double((uint64_t{1} << (8 * type.bytes - 1)) - 1)
                            : double((uint64_t{1} << (8 * type.bytes)) - 1);
  return std::isfinite(value) ? std::clamp(float(value), 0.0f, 1.0f) : 1.0f;
}

double binaryValue(const uint8_t* at, const PlyProperty& type, bool swap) {
  uint8_t raw[8];
  std::memcpy(raw, at, static_cast<size_t>(type.bytes));
  if (swap) std::reverse(raw, raw + type.bytes);
  auto as = [&](auto value) {
    std::memcpy(&value, raw, sizeof value);
    return static_cast<double>(value);
  };
  switch (type.bytes) {
    case 1:
      return type.is_signed ? as(int8_t{}) : as(uint8_t{});
    case 2:
      return type.is_signed ? as(int16_t{}) : as(uint16_t{});
    case 4:
      return type.is_float ? as(float{}) : type.is_signed ? as(int32_t{}) : as(uint32_t{});
    default:
      return as(double{});
  }
}

// Reads each vertex's property values (into `values`) and passes them to `add`; an error when
// the body ends early or an ASCII value is not a number.
template <typename Add>
Expected<void> forEachVertex(std::span<const uint8_t> body, const PlyVertexHeader& header,
                             const std::string& name, Add add) {
  const std::vector<PlyProperty>& properties = header.properties;
  std::vector<double> values(properties.size());
  if (header.format != PlyFormat::kAscii) {
    size_t stride = 0;
    for (const PlyProperty& p : properties) stride += static_cast<size_t>(p.bytes);
    if (stride == 0 || body.size() / stride < header.count)
      return makeError(name + ": the file ends before its " + std::to_string(header.count) +
                       " vertices");
    const bool swap = (header.format == PlyFormat::kBinaryBigEndian) ==
                      (std::endian::native == std::endian::little);
    const uint8_t* at = body.data();
    for (uint64_t v = 0; v < header.count; ++v) {
      for (size_t p = 0; p < properties.size(); ++p) {
        values[p] = binaryValue(at, properties[p], swap);
        at += properties[p].bytes;
      }
      add(values);
    }
    return {};
  }
  const char* at = reinterpret_cast<const char*>(body.data());
  const char* const end = at + body.size();
  for (uint64_t v = 0; v < header.count; ++v) {
    for (size_t p = 0; p < properties.size(); ++p) {
      while (at < end && (*at == ' ' || *at == '\t' || *at == '\r' || *at == '\n')) ++at;
      if (at == end)
        return makeError(name + ": the file ends before its " + std::to_string(header.count) +
                         " vertices");
      const auto [next, error] = std::from_chars(at, end, values[p]);
      if (error != std::errc{} ||
          (next < end && *next != ' ' && *next != '\t' && *next != '\r' && *next != '\n'))
        return makeError(name + ": vertex " + std::to_string(v + 1) + ": property '" +
                         std::string(properties[p].name) + "' is not a number");
      at = next;
    }
    add(values);
  }
  return {};
}

}  // namespace

std::optional<Expected<Model>> readPlyPointCloud(std::span<const uint8_t> bytes,
                                                 const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()),
                              std::min<size_t>(bytes.size(), 64 << 10));
  if (!text.starts_with("ply")) return std::nullopt;
  const std::optional<PlyVertexHeader> header = vertexOnlyHeader(text);
  if (!header) return std::nullopt;
  const VertexLayout layout = layoutOf(header->properties);
  if (layout.index[0] < 0 || layout.index[1] < 0 || layout.index[2] < 0) return std::nullopt;

  Model model;
  model.materials.push_back(Material{});
  PointList& points = model.points;
  points.positions.reserve(header->count);
  const bool colored = layout.colored();
  if (colored) points.colors.reserve(header->count);
  // Channels as sRGB bytes (PointList's packed colours): 8-bit ones, the usual case, as they are.
  const auto& ps = header->properties;
  auto channel = [&](const std::vector<double>& values, int i) -> uint32_t {
    const auto p = static_cast<size_t>(layout.index[static_cast<size_t>(i)]);
    const double value = values[p];
    if (ps[p].bytes == 1 && !ps[p].is_signed && value >= 0 && value <= 255)
      return static_cast<uint32_t>(value);
    return static_cast<uint32_t>(std::lround(unitChannel(value, ps[p]) * 255.0f));
  };
  // A double past float's range is not finite as a position (and its conversion undefined).
  auto coordinate = [&](const std::vector<double>& values, int i) {
    const double value = values[static_cast<size_t>(layout.index[static_cast<size_t>(i)])];
    return std::abs(value) <= double(std::numeric_limits<float>::max())
               ? static_cast<float>(value)
               : std::numeric_limits<float>::infinity();
  };
  size_t dropped = 0;
  Expected<void> read = forEachVertex(
      bytes.subspan(header->body), *header, name, [&](const std::vector<double>& values) {
        const float3 p{coordinate(values, 0), coordinate(values, 1), coordinate(values, 2)};
        if (!isFinite(p)) {
          ++dropped;
          return;
        }
        points.positions.push_back(p);
        if (colored)
          points.colors.push_back(0xff000000u | channel(values, 3) | channel(values, 4) << 8 |
                                  channel(values, 5) << 16);
      });
  if (!read) return Expected<Model>(read.error());
  if (dropped > 0)
    model.warnings.push_back(name + ": " + std::to_string(dropped) +
                             " points at a NaN or infinite position are not drawn");
  if (points.empty())
    return Expected<Model>(makeError(name + ": nothing to draw: no faces, points or lines"));
  return Expected<Model>(std::move(model));
}

}  // namespace tessera::io
