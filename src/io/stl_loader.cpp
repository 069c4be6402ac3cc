// STL, binary and ASCII. The facets become triangles in file order; identical positions are
// welded (so smooth normals can be generated across facets) and the facet normals are ignored:
// exporters often leave them zero or stale, and the winding says the same thing.
#include <tessera/io/model_loader.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "load_budget.h"
#include "model_paths.h"

namespace tessera::io {

namespace {

// 2 GiB: 43 million binary facets, far past what a software renderer draws interactively.
constexpr uintmax_t kMaxStlBytes = uintmax_t{2} << 30;
constexpr size_t kBinaryHeaderBytes = 84;  // 80-byte header + uint32 facet count
constexpr size_t kBinaryFacetBytes = 50;   // normal, 3 vertices (12 floats) + uint16 attribute

// ---- Welding ----

// One vertex per distinct position, by value (-0 and +0 are the same point), in first-use order.
// Open addressing with linear probing over a power-of-two table at most half full.
class PositionWelder {
 public:
  explicit PositionWelder(size_t corner_count) {
    size_t capacity = 16;
    while (capacity < corner_count * 2) capacity *= 2;
    slots_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
  }

  // Index of `p` among the welded positions, adding it if new.
  uint32_t weld(float3 p, std::vector<float3>& positions) {
    const Key key = keyOf(p);
    size_t slot = hash(key) & mask_;
    while (slots_[slot] != kEmpty) {
      if (keyOf(positions[slots_[slot]]) == key) return slots_[slot];
      slot = (slot + 1) & mask_;
    }
    const auto index = static_cast<uint32_t>(positions.size());
    slots_[slot] = index;
    positions.push_back(p);
    return index;
  }

 private:
  struct Key {
    uint32_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  static constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();

  static uint32_t bitsOf(float value) {
    if (value == 0.0f) value = 0.0f;  // -0 -> +0
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
  }
  static Key keyOf(float3 p) { return {bitsOf(p.x), bitsOf(p.y), bitsOf(p.z)}; }
  static size_t hash(const Key& key) {
    uint64_t h = key.x * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ key.y) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 32) ^ key.z) * 0x94D049BB133111EBull;
    return static_cast<size_t>(h ^ (h >> 31));
  }

  std::vector<uint32_t> slots_;
  size_t mask_ = 0;
};

// Facet corners (three per facet, in order) to a welded, indexed mesh with smooth normals.
Model buildModel(const std::vector<float3>& corners, const std::string& name,
                 std::string_view first_nonfinite_at) {
  Model model;
  model.materials.push_back(Material{});
  Mesh& mesh = model.mesh;
  PositionWelder welder(corners.size());
  mesh.indices.reserve(corners.size());
  for (size_t i = 0; i < corners.size(); i += 3) {
    bool finite = true;
    for (size_t c = 0; c < 3; ++c) {
      mesh.indices.push_back(welder.weld(corners[i + c], mesh.positions));
      finite &= isFinite(corners[i + c]);
    }
    if (!finite) ++model.nonfinite_triangles;
  }
  generateSmoothNormals(mesh);
  if (model.nonfinite_triangles > 0)
    model.warnings.push_back(name + ": " + std::to_string(model.nonfinite_triangles) +
                             " facets have a NaN or infinite vertex (the first at " +
                             std::string(first_nonfinite_at) +
                             "); they are kept so triangle ids stay in facet order, and not drawn");
  return model;
}

// ---- Binary ----

float floatAt(const uint8_t* p) {
  // STL is little-endian, as is every machine tessera targets.
  static_assert(std::endian::native == std::endian::little, "STL floats are little-endian");
  float value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

Expected<Model> parseBinary(std::span<const uint8_t> bytes, uint32_t facet_count,
                            const LoadBudget& budget, const std::string& name) {
  if (Expected<void> ok =
          checkBudget(name, "facets", facet_count, budget.triangles(), "--max-triangles");
      !ok)
    return ok.error();
  std::vector<float3> corners(size_t{facet_count} * 3);
  std::string first_nonfinite;
  const uint8_t* facet = bytes.data() + kBinaryHeaderBytes;
  for (size_t f = 0; f < facet_count; ++f, facet += kBinaryFacetBytes) {
    // Bytes 0-11 are the facet normal, ignored.
    for (size_t c = 0; c < 3; ++c) {
      const uint8_t* v = facet + 12 + 12 * c;
      float3 p{floatAt(v), floatAt(v + 4), floatAt(v + 8)};
      corners[3 * f + c] = p;
      if (!isFinite(p) && first_nonfinite.empty())
        first_nonfinite = "facet " + std::to_string(f + 1);
    }
  }
  return buildModel(corners, name, first_nonfinite);
}

// ---- ASCII ----

// Splits the text into blank-separated words, counting lines.
class Words {
 public:
  explicit Words(std::string_view text) : text_(text) {}

  // The next word, or empty at the end of the text.
  std::string_view next() {
    skipBlanks();
    size_t begin = at_;
    while (at_ < text_.size() && !isBlank(text_[at_])) ++at_;
    word_line_ = line_;
    return text_.substr(begin, at_ - begin);
  }
  // Skips the rest of the current line (a solid's name).
  void skipLine() {
    while (at_ < text_.size() && text_[at_] != '\n' && text_[at_] != '\r') ++at_;
  }
  // The line of the word last returned.
  uint32_t line() const { return word_line_; }

 private:
  static bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v' || c == '\0';
  }
  void skipBlanks() {
    while (at_ < text_.size() && isBlank(text_[at_])) {
      // "\r\n" counts once; a lone '\r' (old Mac files) counts as a line end too.
      if (text_[at_] == '\n' ||
          (text_[at_] == '\r' && (at_ + 1 >= text_.size() || text_[at_ + 1] != '\n')))
        ++line_;
      ++at_;
    }
  }

  std::string_view text_;
  size_t at_ = 0;
  uint32_t line_ = 1;
  uint32_t word_line_ = 1;
};

// A number as exporters write them: optional sign, decimal or exponent form, nan, inf.
// Magnitudes beyond float become infinite (or zero, for tiny ones).
bool parseNumber(std::string_view word, float& value) {
  std::string_view digits = word;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  if (digits.empty()) return false;
  const char* end = digits.data() + digits.size();
  auto [stop, error] = std::from_chars(digits.data(), end, value);
  if (stop != end) return false;
  if (error == std::errc::result_out_of_range) {
    double wide = 0;
    auto [wide_stop, wide_error] = std::from_chars(digits.data(), end, wide);
    const bool negative = digits.front() == '-';
    if (wide_error == std::errc() && wide_stop == end && std::fabs(wide) <= 1.0) {
      value = negative ? -0.0f : 0.0f;  // underflow
    } else if (wide_error == std::errc() && wide_stop == end) {
      value = negative ? -std::numeric_limits<float>::infinity()
                       : std::numeric_limits<float>::infinity();
    } else {
      // Beyond double too: the exponent's sign says which way.
      const size_t e = digits.find_first_of("eE");
      const bool tiny =
          e != std::string_view::npos && e + 1 < digits.size() && digits[e + 1] == '-';
      const float big = std::numeric_limits<float>::infinity();
      value = tiny ? (negative ? -0.0f : 0.0f) : (negative ? -big : big);
    }
    return true;
  }
  return error == std::errc();
}

bool keywordIs(std::string_view word, std::string_view keyword) {
  return equalsIgnoreCase(word, keyword);
}

// A word as an error message shows it: quoted, cut at 40 bytes, control bytes as '?'.
std::string shown(std::string_view word) {
  if (word.empty()) return std::string("the end of the file");
  if (word.size() > 40) word = word.substr(0, 40);
  std::string text = "'";
  for (char c : word) text += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  return text + "'";
}

// The words of an ASCII STL file read as its grammar says, each error naming its line.
class AsciiReader {
 public:
  AsciiReader(std::string_view text, const std::string& name) : words_(text), name_(name) {}
  Words& words() { return words_; }
  // "name:line: ", the start of an error message about `line`.
  std::string at(uint32_t line) const { return name_ + ":" + std::to_string(line) + ": "; }
  Expected<void> expect(std::string_view keyword) {
    std::string_view word = words_.next();
    if (keywordIs(word, keyword)) return {};
    return makeError(at(words_.line()) + "expected '" + std::string(keyword) + "', found " +
                     shown(word));
  }
  Expected<void> readVector(float3& v) {
    for (int i = 0; i < 3; ++i) {
      std::string_view word = words_.next();
      if (!parseNumber(word, v[i]))
        return makeError(at(words_.line()) + "expected a number, found " + shown(word));
    }
    return {};
  }
  // A facet after its `facet` keyword, through `endfacet`: its three corners appended to
  // `corners`; `first_nonfinite` names the line of the first corner that is not finite.
  Expected<void> readFacet(std::vector<float3>& corners, std::string& first_nonfinite) {
    const uint32_t facet_line = words_.line();
    float3 normal;
    if (Expected<void> ok = expect("normal"); !ok) return ok;
    if (Expected<void> ok = readVector(normal); !ok) return ok;
    if (Expected<void> ok = expect("outer"); !ok) return ok;
    if (Expected<void> ok = expect("loop"); !ok) return ok;
    size_t vertices = 0;
    while (true) {
      const std::string_view word = words_.next();
      if (keywordIs(word, "endloop")) break;
      if (!keywordIs(word, "vertex"))
        return makeError(at(words_.line()) + "expected 'vertex' or 'endloop', found " +
                         shown(word));
      float3 p;
      if (Expected<void> ok = readVector(p); !ok) return ok;
      if (++vertices > 3)
        return makeError(at(facet_line) +
                         "a facet with more than 3 vertices; STL facets are triangles");
      corners.push_back(p);
      if (!isFinite(p) && first_nonfinite.empty())
        first_nonfinite = "line " + std::to_string(words_.line());
    }
    if (vertices != 3)
      return makeError(at(facet_line) + "a facet with " + std::to_string(vertices) +
                       " vertices; STL facets are triangles");
    return expect("endfacet");
  }

 private:
  Words words_;
  const std::string& name_;
};

Expected<Model> parseAscii(std::string_view text, const std::string& name,
                           const LoadBudget& budget) {
  AsciiReader reader(text, name);
  Words& words = reader.words();
  std::vector<float3> corners;
  std::string first_nonfinite;
  std::string_view word = words.next();
  if (!keywordIs(word, "solid"))
    return makeError(name + ": not an STL file (neither binary nor ASCII starting with 'solid')");
  words.skipLine();
  bool in_solid = true;
  while (true) {
    word = words.next();
    if (word.empty()) break;  // A missing final `endsolid` is forgiven.
    if (keywordIs(word, "endsolid")) {
      words.skipLine();
      in_solid = false;
      continue;
    }
    if (keywordIs(word, "solid") && !in_solid) {
      words.skipLine();
      in_solid = true;
      continue;
    }
    if (!keywordIs(word, "facet") || !in_solid)
      return makeError(reader.at(words.line()) + "expected 'facet' or 'endsolid', found " +
                       shown(word));
    if (Expected<void> ok = reader.readFacet(corners, first_nonfinite); !ok) return ok.error();
    if (Expected<void> ok =
            checkBudget(name, "facets", corners.size() / 3, budget.triangles(), "--max-triangles");
        !ok)
      return ok.error();
  }
  if (corners.empty()) return makeError(name + ": no triangles (the file has no facets)");
  if (corners.size() > std::numeric_limits<uint32_t>::max())
    return makeError(name + ": too many facets");
  return buildModel(corners, name, first_nonfinite);
}

// ---- Which kind ----

bool startsWithSolid(std::span<const uint8_t> bytes) {
  size_t i = 0;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data() + i), bytes.size() - i);
  return text.size() >= 5 && equalsIgnoreCase(text.substr(0, 5), "solid") &&
         (text.size() == 5 || std::isspace(static_cast<unsigned char>(text[5])));
}

// Bytes that text never holds: NUL and control characters other than blanks and line ends.
bool hasControlBytes(std::span<const uint8_t> bytes) {
  for (uint8_t b : bytes)
    if (b < 0x20 && b != '\t' && b != '\n' && b != '\r' && b != '\f' && b != '\v') return true;
  return false;
}

Expected<Model> parseStl(std::span<const uint8_t> bytes, const std::string& name,
                         const LoadBudget& budget) {
  if (bytes.empty()) return makeError(name + ": the file is empty: no triangles");
  if (bytes.size() > kMaxStlBytes)
    return makeError(name + ": the file is " + std::to_string(bytes.size()) +
                     " bytes; STL files over 2 GiB are refused");
  const bool ascii_start = startsWithSolid(bytes);
  if (bytes.size() >= kBinaryHeaderBytes) {
    uint32_t facet_count;
    std::memcpy(&facet_count, bytes.data() + 80, sizeof facet_count);
    // 64-bit, so a count near 2^32 cannot wrap the product.
    const uint64_t binary_size = kBinaryHeaderBytes + uint64_t{kBinaryFacetBytes} * facet_count;
    // Exporters write "solid" into binary headers too: the exact size decides.
    if (binary_size == bytes.size()) {
      if (facet_count == 0) return makeError(name + ": no triangles (the binary STL has 0 facets)");
      return parseBinary(bytes, facet_count, budget, name);
    }
    if (!ascii_start) {
      if (binary_size > bytes.size())
        return makeError(name + ": truncated or corrupt binary STL: the header says " +
                         std::to_string(facet_count) + " facets (" + std::to_string(binary_size) +
                         " bytes), the file has " + std::to_string(bytes.size()) + " bytes");
      if (facet_count == 0) return makeError(name + ": no triangles (the binary STL has 0 facets)");
      Expected<Model> model = parseBinary(bytes, facet_count, budget, name);
      if (model)
        model->warnings.push_back(name + ": " + std::to_string(bytes.size() - binary_size) +
                                  " bytes after the last facet ignored");
      return model;
    }
  } else if (!ascii_start) {
    return makeError(name + ": truncated binary STL: " + std::to_string(bytes.size()) +
                     " bytes, shorter than the 84-byte header");
  }
  Expected<Model> model = parseAscii(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), name, budget);
  if (model || bytes.size() < kBinaryHeaderBytes || !hasControlBytes(bytes)) return model;
  // A binary file whose header starts with "solid" and whose size is off: say so, rather than
  // only how its bytes fail as text.
  uint32_t facet_count;
  std::memcpy(&facet_count, bytes.data() + 80, sizeof facet_count);
  const uint64_t binary_size = kBinaryHeaderBytes + uint64_t{kBinaryFacetBytes} * facet_count;
  return makeError(name + ": truncated or corrupt binary STL: the header says " +
                   std::to_string(facet_count) + " facets (" + std::to_string(binary_size) +
                   " bytes), the file has " + std::to_string(bytes.size()) +
                   " bytes (its header starts with 'solid', but it is not ASCII STL either: " +
                   model.error().message + ")");
}

template <typename Load>
Expected<Model> guarded(const std::string& name, Load load) {
  try {
    return load();
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::length_error&) {
    return makeError(name + ": out of memory while loading");
  }
}

}  // namespace

Expected<Model> loadStlFromMemory(std::span<const uint8_t> bytes, const std::string& name,
                                  const LoadBudget& budget) {
  return guarded(name, [&] { return parseStl(bytes, name, budget); });
}

Expected<Model> loadStl(const std::filesystem::path& path, const LoadBudget& budget) {
  const std::string name = path.string();
  return guarded(name, [&]() -> Expected<Model> {
    Expected<std::vector<unsigned char>> bytes =
        readRegularFile(path, std::min<uint64_t>(kMaxStlBytes, budget.fileBytes()), "STL");
    if (!bytes) return bytes.error();
    return parseStl(*bytes, name, budget);
  });
}

}  // namespace tessera::io
