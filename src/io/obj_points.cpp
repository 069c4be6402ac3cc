#include "obj_points.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <tessera/scene/color.h>

namespace tessera::io {

namespace {

float3 positionAt(const tinyobj::attrib_t& attrib, size_t i) {
  return float3{attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
}

// An sRGB-encoded `v` colour as PointList packs it (8-bit sRGB); a channel that is not finite is
// white.
uint32_t pointColor(const tinyobj::attrib_t& attrib, size_t i) {
  uint32_t packed = 0xff000000u;
  for (int c = 0; c < 3; ++c) {
    const float value = attrib.colors[3 * i + static_cast<size_t>(c)];
    const float unit = std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 1.0f;
    packed |= static_cast<uint32_t>(std::lround(unit * 255.0f)) << (8 * c);
  }
  return packed;
}

// Per `usemtl` name of the scan: the segment colour, the material's Kd when its MTL block set one,
// else the default material's.
std::vector<float3> lineColors(const ObjElements& elements,
                               const std::vector<tinyobj::material_t>& library_materials,
                               const FolderMaterialReader& reader) {
  const float3 fallback = Material{}.base_color.xyz();
  std::unordered_map<std::string, size_t> library_index;
  for (size_t i = 0; i < library_materials.size(); ++i)
    library_index.try_emplace(library_materials[i].name, i);  // the first, as tinyobjloader
  std::vector<float3> colors(elements.material_names.size(), fallback);
  for (size_t m = 1; m < colors.size(); ++m) {
    auto found = library_index.find(elements.material_names[m]);
    if (found == library_index.end() || !reader.hasKd(found->second)) continue;
    const tinyobj::material_t& source = library_materials[found->second];
    for (int c = 0; c < 3; ++c) {
      const float value = source.diffuse[c];
      colors[m][c] = std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback[c];
    }
  }
  return colors;
}

}  // namespace

bool hasFaceLines(const ObjLineIndex& lines) {
  return !lines.face_lines.empty() || lines.short_faces > 0;
}

uint64_t objPointBudgetCount(const ObjLineIndex& lines) {
  const ObjElements& elements = lines.elements;
  const uint64_t counted = elements.point_vertices + 2 * elements.line_segments;
  if (counted == 0 && !hasFaceLines(lines)) return lines.positions;
  return counted;
}

Expected<void> addObjPointsAndLines(const std::string& name, const tinyobj::attrib_t& attrib,
                                    const ObjLineIndex& lines,
                                    const std::vector<tinyobj::material_t>& library_materials,
                                    const FolderMaterialReader& reader, Model& model) {
  const ObjElements& elements = lines.elements;
  const size_t position_count = attrib.vertices.size() / 3;
  const bool has_colors = !attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size();
  PointList& points = model.points;
  size_t dropped = 0;
  auto addPoint = [&](size_t i) {
    const float3 p = positionAt(attrib, i);
    if (!isFinite(p)) {
      ++dropped;
      return;
    }
    points.positions.push_back(p);
    if (has_colors) points.colors.push_back(pointColor(attrib, i));
  };

  if (!hasFaceLines(lines) && elements.elements.empty()) {
    // Vertices without faces, points or lines: a point cloud.
    points.positions.reserve(position_count);
    if (has_colors) points.colors.reserve(position_count);
    for (size_t i = 0; i < position_count; ++i) addPoint(i);
  } else {
    const std::vector<float3> colors = lineColors(elements, library_materials, reader);
    for (const ObjElements::Element& element : elements.elements) {
      for (uint64_t v = element.first; v < element.first + element.count; ++v) {
        const int64_t index = elements.indices[v];
        if (index < 0 || static_cast<uint64_t>(index) >= position_count)
          return makeError(name + ":" + std::to_string(element.line) + ": " +
                           (element.polyline ? "line" : "point") + " index " +
                           (index < 0 ? std::string("reaches before the first position")
                                      : std::to_string(index + 1) + " is past the end (" +
                                            std::to_string(position_count) + " positions)"));
      }
      const int64_t* at = &elements.indices[element.first];
      if (!element.polyline) {
        for (uint32_t v = 0; v < element.count; ++v) addPoint(static_cast<size_t>(at[v]));
        continue;
      }
      for (uint32_t v = 1; v < element.count; ++v) {
        const float3 a = positionAt(attrib, static_cast<size_t>(at[v - 1]));
        const float3 b = positionAt(attrib, static_cast<size_t>(at[v]));
        if (isFinite(a) && isFinite(b))
          model.lines.add(a, b, colors[element.material]);
        else
          ++dropped;
      }
    }
  }
  if (dropped > 0)
    model.warnings.push_back(
        name + ": " + std::to_string(dropped) +
        " points or line segments at a NaN or infinite position are not drawn");
  return {};
}

}  // namespace tessera::io
