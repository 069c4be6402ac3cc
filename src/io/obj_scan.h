// The light passes over OBJ and MTL text that run before tinyobjloader: lines split as it splits
// them, the faces and material libraries it will see (with their lines, for messages), what it
// would misread (face indices past 32 bits, `nan` and `inf`), and the counts the budget is
// checked against before it allocates. Private to tessera_io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::io {

// tinyobjloader stores a face's corner count in an unsigned char.
constexpr size_t kMaxFaceCorners = 255;

inline bool isBlank(char c) {
  return c == ' ' || c == '\t';
}

// Calls `visit(line, number)` for each line, split as tinyobjloader splits them (\n, \r\n and a
// lone \r) and cut at a NUL, since tinyobjloader reads each line as a C string.
template <typename Visit>
void forEachLine(std::istream& in, Visit visit) {
  uint32_t number = 0;
  std::string raw;
  while (std::getline(in, raw)) {
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    size_t begin = 0;
    while (true) {
      size_t end = raw.find('\r', begin);
      std::string_view line = std::string_view(raw).substr(
          begin, (end == std::string::npos ? raw.size() : end) - begin);
      visit(line.substr(0, line.find('\0')), ++number);
      if (end == std::string::npos) break;
      begin = end + 1;
    }
  }
}

std::string_view skipBlanks(std::string_view line);

// `keyword` followed by a blank, as tinyobjloader matches its keywords.
bool startsWithKeyword(std::string_view line, std::string_view keyword);

// The OBJ's `p` and `l` elements, read by the line pass rather than taken from tinyobjloader, which
// keeps no material for them and, at each change of `usemtl`, copies the points and lines read so
// far into the shape again (tinyobjloader 2.0.0rc: its usemtl clears only the face group).
struct ObjElements {
  struct Element {
    uint64_t first;     // into `indices`
    uint32_t count;     // vertices
    uint32_t line;      // in the file
    uint32_t material;  // the `usemtl` in force: into `material_names`, 0 for none
    bool polyline;      // `l` (consecutive pairs are segments), else `p`
  };
  // 0-based position indices, relative ones resolved against the positions before them (as
  // tinyobjloader does); not yet checked against the position count.
  std::vector<int64_t> indices;
  std::vector<Element> elements;
  std::vector<std::string> material_names{""};
  uint64_t point_vertices = 0;  // counted even past the cap the scan stores up to
  uint64_t line_segments = 0;   // n - 1 for a polyline of n vertices
};

// What a light pass over the OBJ's lines finds, splitting lines as tinyobjloader does (\n, \r\n
// and a lone \r) and spotting `f` and `mtllib` lines as it does. tinyobjloader does not report
// which line a face came from; this does, for error messages.
struct ObjLineIndex {
  std::vector<uint32_t> face_lines;   // line of every face tinyobjloader keeps (3+ corners)
  size_t short_faces = 0;             // faces with fewer than 3 corners (tinyobjloader drops them)
  uint32_t first_long_face_line = 0;  // first face with more corners than tinyobjloader records
  size_t first_long_face_corners = 0;
  std::vector<std::string> material_libraries;  // the text after each `mtllib`, as written
  uint64_t positions = 0;                       // `v` lines
  uint64_t triangles = 0;                       // after splitting every face
  // Positions written as nan or inf, which tinyobjloader reads as 0.
  std::vector<uint64_t> nonfinite_positions;
  ObjElements elements;
  // The first face index outside int (tinyobjloader would wrap it), as written, and its line.
  std::string bad_index;
  uint32_t bad_index_line = 0;
};

// `max_element_vertices` caps the `p` and `l` vertices stored (they are counted past it, so the
// budget check that follows fails with the true count).
ObjLineIndex scanObjLines(std::istream& in, uint64_t max_element_vertices);

// Names of the materials in an MTL text that set Kd. tinyobjloader does not say whether Kd was
// given: it puts 0.6 in its place for a textured material, or 0 once any earlier material had a
// Kd (its flag is never reset). Either would darken the texture; without Kd, the texture is
// meant as it is.
std::set<std::string> materialsWithKd(std::istream& in);

}  // namespace tessera::io
