#include "obj_scan.h"

#include <algorithm>
#include <charconv>
#include <unordered_map>

namespace tessera::io {

namespace {

// A face corner's index that tinyobjloader would wrap (it reads them into int without a range
// check): a run of digits past 2^31 - 1. Returns the offending number, or empty.
std::string outOfRangeIndex(std::string_view corner) {
  size_t begin = 0;
  while (begin <= corner.size()) {
    size_t end = std::min(corner.find('/', begin), corner.size());
    std::string_view part = corner.substr(begin, end - begin);
    begin = end + 1;
    std::string_view digits =
        part.starts_with('-') || part.starts_with('+') ? part.substr(1) : part;
    if (digits.empty() ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    digits.remove_prefix(std::min(digits.find_first_not_of('0'), digits.size()));
    if (digits.size() > 10 || (digits.size() == 10 && digits > "2147483647"))
      return std::string(part);
  }
  return {};
}

// Whether a number token is a NaN or an infinity (nan, -inf, Infinity...).
bool isNonFiniteToken(std::string_view token) {
  if (token.starts_with('-') || token.starts_with('+')) token.remove_prefix(1);
  return !token.empty() &&
         (token[0] == 'n' || token[0] == 'N' || token[0] == 'i' || token[0] == 'I');
}

// The blank-separated tokens of `line` after its keyword.
template <typename Visit>
void forEachToken(std::string_view line, Visit visit) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (i > start) visit(line.substr(start, i - start));
  }
}

void scanFaceLine(std::string_view line, uint32_t line_number, ObjLineIndex& index) {
  size_t corners = 0;
  forEachToken(line.substr(2), [&](std::string_view corner) {
    ++corners;
    if (index.bad_index.empty()) {
      index.bad_index = outOfRangeIndex(corner);
      if (!index.bad_index.empty()) index.bad_index_line = line_number;
    }
  });
  if (corners < 3) {
    ++index.short_faces;
    return;
  }
  index.face_lines.push_back(line_number);
  index.triangles += corners - 2;
  if (corners > kMaxFaceCorners && index.first_long_face_line == 0) {
    index.first_long_face_line = line_number;
    index.first_long_face_corners = corners;
  }
}

void scanPositionLine(std::string_view line, ObjLineIndex& index) {
  int coordinate = 0;
  bool finite = true;
  forEachToken(line.substr(2), [&](std::string_view token) {
    if (coordinate++ < 3 && isNonFiniteToken(token)) finite = false;
  });
  if (!finite) index.nonfinite_positions.push_back(index.positions);
  ++index.positions;
}

// The position a `p` or `l` vertex ("7", "-2", "7/3") names, 0-based, or -1 when it is not a
// number (tinyobjloader fails on the file then) or 0.
int64_t elementIndex(std::string_view token, uint64_t positions_before) {
  token = token.substr(0, token.find('/'));
  int64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc{} || value == 0) return -1;
  return value > 0 ? value - 1 : static_cast<int64_t>(positions_before) + value;
}

// The `usemtl` names met so far, numbered for ObjElements::Element::material.
struct MaterialNames {
  std::unordered_map<std::string, uint32_t> ids{{"", 0}};
  uint32_t current = 0;
};

void scanElementLine(std::string_view line, uint32_t line_number, uint64_t cap,
                     const MaterialNames& materials, ObjLineIndex& index) {
  ObjElements& out = index.elements;
  const bool polyline = line[0] == 'l';
  ObjElements::Element element{out.indices.size(), 0, line_number, materials.current, polyline};
  uint64_t vertices = 0;
  forEachToken(line.substr(2), [&](std::string_view token) {
    ++vertices;
    if (index.bad_index.empty()) {
      index.bad_index = outOfRangeIndex(token);
      if (!index.bad_index.empty()) index.bad_index_line = line_number;
    }
    if (out.indices.size() < cap) {
      out.indices.push_back(elementIndex(token, index.positions));
      ++element.count;
    }
  });
  if (polyline)
    out.line_segments += vertices > 0 ? vertices - 1 : 0;
  else
    out.point_vertices += vertices;
  if (element.count > 0) out.elements.push_back(element);
}

// tinyobjloader's `usemtl` name: the first word after the keyword.
void scanUseMaterial(std::string_view line, MaterialNames& materials, ObjElements& out) {
  std::string_view rest = skipBlanks(line.substr(7));
  std::string name(rest.substr(0, std::min(rest.find_first_of(" \t"), rest.size())));
  auto [slot, added] = materials.ids.try_emplace(name, static_cast<uint32_t>(materials.ids.size()));
  if (added) out.material_names.push_back(std::move(name));
  materials.current = slot->second;
}

void scanObjLine(std::string_view line, uint32_t line_number, uint64_t cap,
                 MaterialNames& materials, ObjLineIndex& index) {
  line = skipBlanks(line);
  if (startsWithKeyword(line, "p") || startsWithKeyword(line, "l")) {
    scanElementLine(line, line_number, cap, materials, index);
  } else if (startsWithKeyword(line, "usemtl")) {
    scanUseMaterial(line, materials, index.elements);
  } else if (startsWithKeyword(line, "f")) {
    scanFaceLine(line, line_number, index);
  } else if (startsWithKeyword(line, "v")) {
    scanPositionLine(line, index);
  } else if (startsWithKeyword(line, "mtllib")) {
    index.material_libraries.emplace_back(line.substr(7));
  }
}

}  // namespace

std::string_view skipBlanks(std::string_view line) {
  size_t start = 0;
  while (start < line.size() && isBlank(line[start])) ++start;
  return line.substr(start);
}

bool startsWithKeyword(std::string_view line, std::string_view keyword) {
  return line.size() > keyword.size() && line.starts_with(keyword) && isBlank(line[keyword.size()]);
}

ObjLineIndex scanObjLines(std::istream& in, uint64_t max_element_vertices) {
  ObjLineIndex index;
  MaterialNames materials;
  forEachLine(in, [&](std::string_view line, uint32_t number) {
    scanObjLine(line, number, max_element_vertices, materials, index);
  });
  return index;
}

std::set<std::string> materialsWithKd(std::istream& in) {
  std::set<std::string> names;
  std::string current;
  forEachLine(in, [&](std::string_view line, uint32_t) {
    line = skipBlanks(line);
    if (startsWithKeyword(line, "newmtl")) {
      std::string rest(line.substr(7));
      current = rest.substr(0, rest.find_last_not_of(" \t") + 1);  // as tinyobjloader trims
    } else if (startsWithKeyword(line, "Kd")) {
      names.insert(current);
    }
  });
  return names;
}

}  // namespace tessera::io
