// PLY headers and OFF files, checked before assimp reads them (assimp_headers.h).
#include "assimp_headers.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <string_view>
#include <system_error>

#include "load_budget.h"
#include "model_paths.h"

namespace tessera::io {

namespace {

// The first `max_words` blank-separated words of `text`, '#' comments skipped (OFF).
std::vector<std::string_view> headerWords(std::string_view text, size_t max_words) {
  std::vector<std::string_view> words;
  size_t at = 0;
  while (at < text.size() && words.size() < max_words) {
    const char c = text[at];
    if (c == '#') {
      while (at < text.size() && text[at] != '\n') ++at;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++at;
    } else {
      const size_t begin = at;
      while (at < text.size() && !std::isspace(static_cast<unsigned char>(text[at]))) ++at;
      words.push_back(text.substr(begin, at - begin));
    }
  }
  return words;
}

uint64_t parseCount(std::string_view word) {
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc{} ? value : 0;
}

// A count a header declares, against the budget and against what the file can hold: every
// element takes at least one byte, so a count past the file's size is a lie assimp would
// allocate for.
Expected<void> checkDeclared(const std::string& name, const std::string& what, uint64_t count,
                             uint64_t budget, size_t file_bytes,
                             const std::string& flag = "--max-triangles") {
  if (count > file_bytes)
    return makeError(name + ": the header declares " + std::to_string(count) + " " + what +
                     ", more than the file's " + std::to_string(file_bytes) + " bytes can hold");
  return checkBudget(name, what, count, budget, flag);
}

bool isPlyType(std::string_view word) {
  for (std::string_view type :
       {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
        "int16", "uint16", "int32", "uint32", "float32", "float64"})
    if (word == type) return true;
  return false;
}

// A PLY header, line by line, before assimp sees it: assimp 5.2's PLY reader loops forever on
// some broken headers (a NUL inside a keyword, found by fuzz/assimp_fuzz.cpp), so only the
// header grammar goes through: printable lines, well-formed `format`, `element NAME COUNT` and
// `property [list TYPE] TYPE NAME` lines, up to `end_header` (other lines are skipped, as assimp
// skips them). The counts an element declares are checked against the budget and the file's
// size: assimp sizes its arrays from them. An element name declared twice is refused: assimp
// sizes its vertex arrays from one `element vertex` and fills them from both, writing past
// their end (fuzz/corpus/assimp/overflow_vertex_twice.ply).
Expected<void> checkPlyHeader(std::string_view text, const std::string& name,
                              const LoadBudget& budget, size_t file_bytes) {
  size_t line_number = 0, at = 0;
  bool in_element = false;
  std::vector<std::string_view> elements;  // the names declared so far
  // The vertex count is checked at end_header: a PLY without faces is a point cloud, whose
  // vertices are points (LoadBudget::points()).
  uint64_t vertices = 0, faces = 0;
  while (at < text.size()) {
    const size_t end = std::min(text.find('\n', at), text.size());
    std::string_view line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    if (line.ends_with('\r')) line.remove_suffix(1);
    const auto bad = [&](const std::string& why) {
      return makeError(name + ": line " + std::to_string(line_number) + ": " + why +
                       " in the PLY header");
    };
    for (char c : line)
      if ((c < 0x20 || c > 0x7e) && c != '\t') return bad("a control or non-ASCII byte");
    const std::vector<std::string_view> words = headerWords(line, 8);
    if (words.empty()) continue;
    const std::string_view key = words[0];
    if (line_number == 1) {
      if (key != "ply" || words.size() != 1) return bad("'ply' expected");
    } else if (key == "end_header") {
      if (faces == 0)
        return checkDeclared(name, "vertices (points: the file has no faces)", vertices,
                             budget.points(), file_bytes, "");
      return checkDeclared(name, "vertices", vertices, budget.vertices(), file_bytes);
    } else if (key == "format") {
      if (words.size() != 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" &&
                                words[1] != "binary_big_endian"))
        return bad("an unknown format");
    } else if (key == "element") {
      if (words.size() != 3 || words[2].find_first_not_of("0123456789") != std::string_view::npos)
        return bad("'element NAME COUNT' expected");
      if (std::find(elements.begin(), elements.end(), words[1]) != elements.end())
        return bad("a second " + singleQuoted(elided(words[1])) + " element");
      elements.push_back(words[1]);
      const uint64_t count = parseCount(words[2]);
      if (words[1] == "vertex") vertices = count;
      if (words[1] == "face") faces = count;
      // Vertices are checked against their budget at end_header, once faces are known.
      const uint64_t limit = words[1] == "face" ? budget.triangles() : UINT64_MAX;
      const std::string what = words[1] == "vertex" ? "vertices"
                               : words[1] == "face" ? "faces"
                                                    : singleQuoted(elided(words[1])) + " elements";
      if (Expected<void> ok = checkDeclared(name, what, count, limit, file_bytes); !ok) return ok;
      in_element = true;
    } else if (key == "property") {
      const bool list =
          words.size() == 5 && words[1] == "list" && isPlyType(words[2]) && isPlyType(words[3]);
      if (!in_element || !(list || (words.size() == 3 && isPlyType(words[1]))))
        return bad("'property TYPE NAME' or 'property list TYPE TYPE NAME' expected");
    }
    // Any other line is skipped, as assimp does (Blender 2.4 wrote "Created by Blender3D...").
  }
  return makeError(name + ": the PLY header has no end_header in its first 64 KiB");
}

// An OFF file, line by line ('#' comments, blank lines skipped): a header word ending in "OFF"
// (OFF, COFF, NOFF, STOFF...), the counts V F E (on that line or the next), V vertex lines of at
// least three numbers, then F faces of "n i1 ... in" with 3 <= n and every index below V.
Expected<void> checkOffFile(std::string_view text, const std::string& name,
                            const LoadBudget& budget) {
  size_t at = 0, line_number = 0;
  std::vector<std::string_view> words;
  // The words of the next line that has any; false at the end of the file.
  const auto nextLine = [&]() {
    while (at < text.size()) {
      const size_t end = std::min(text.find('\n', at), text.size());
      words = headerWords(text.substr(at, end - at), 64);
      at = end + 1;
      ++line_number;
      if (!words.empty()) return true;
    }
    return false;
  };
  const auto bad = [&](const std::string& why) {
    return makeError(name + ": line " + std::to_string(line_number) + ": " + why);
  };
  if (!nextLine() || !words[0].ends_with("OFF") || words[0].size() > 5)
    return makeError(name + ": not an OFF file (it does not start with OFF)");
  std::vector<std::string_view> counts(words.begin() + 1, words.end());
  if (counts.empty() && nextLine()) counts = words;
  if (counts.size() < 2) return bad("'VERTICES FACES [EDGES]' expected");
  for (size_t i = 0; i < std::min<size_t>(counts.size(), 3); ++i)
    if (counts[i].empty() || counts[i].find_first_not_of("0123456789") != std::string_view::npos)
      return bad("'VERTICES FACES [EDGES]' expected");
  const uint64_t vertices = parseCount(counts[0]), faces = parseCount(counts[1]);
  if (Expected<void> ok = checkDeclared(name, "vertices", vertices, budget.vertices(), text.size());
      !ok)
    return ok;
  if (Expected<void> ok = checkDeclared(name, "faces", faces, budget.triangles(), text.size()); !ok)
    return ok;
  for (uint64_t v = 0; v < vertices; ++v) {
    if (!nextLine())
      return bad("the file ends before its " + std::to_string(vertices) + " vertices");
    if (words.size() < 3) return bad("a vertex of fewer than three numbers");
  }
  for (uint64_t f = 0; f < faces; ++f) {
    if (!nextLine()) return bad("the file ends before its " + std::to_string(faces) + " faces");
    if (words[0].find_first_not_of("0123456789") != std::string_view::npos)
      return bad("a face's vertex count expected");
    const uint64_t n = parseCount(words[0]);
    if (n < 3) return bad("a face of " + std::to_string(n) + " vertices");
    if (n + 1 > words.size()) return bad("a face with fewer indices than it says");
    for (size_t i = 1; i <= n; ++i)
      if (words[i].find_first_not_of("0123456789") != std::string_view::npos ||
          parseCount(words[i]) >= vertices)
        return bad("face index " + elided(words[i]) + " is not one of the " +
                   std::to_string(vertices) + " vertices");
  }
  return {};
}

}  // namespace

uint64_t plyDeclaredFaces(const std::vector<uint8_t>& bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()),
                              std::min<size_t>(bytes.size(), 64 << 10));
  if (!text.starts_with("ply")) return 0;
  uint64_t faces = 0;
  for (size_t at = 0; at < text.size();) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::vector<std::string_view> words = headerWords(text.substr(at, end - at), 4);
    at = end + 1;
    if (!words.empty() && words[0] == "end_header") break;
    if (words.size() == 3 && words[0] == "element" && words[1] == "face")
      faces += parseCount(words[2]);
  }
  return faces;
}

Expected<void> checkHeaders(const std::vector<uint8_t>& bytes, const std::string& name,
                            const std::string& extension, const LoadBudget& budget) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text.starts_with("ply"))
    return checkPlyHeader(text.substr(0, std::min<size_t>(text.size(), 64 << 10)), name, budget,
                          bytes.size());
  const std::vector<std::string_view> first = headerWords(text.substr(0, 64), 1);
  const bool looks_off = !first.empty() && first[0].ends_with("OFF") && first[0].size() <= 5;
  if (extension == "off" || looks_off) return checkOffFile(text, name, budget);
  return {};
}

}  // namespace tessera::io
