// OBJ material libraries (obj_materials.h), split from obj_loader.cpp.
#include "obj_materials.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>

#include "model_paths.h"
#include "obj_scan.h"

namespace tessera::io {

namespace {

namespace fs = std::filesystem;

// MTL files are a few kilobytes of text; one this big is not a material library.
constexpr uintmax_t kMaxMtlBytes = uintmax_t{64} << 20;
// Distinct tinyobjloader warnings passed on per file; the rest are counted.
constexpr size_t kMaxLibraryWarnings = 10;

// The text between the first two `quote`s, or empty.
std::string_view between(std::string_view text, char quote) {
  const size_t begin = text.find(quote);
  const size_t end = begin == std::string_view::npos ? begin : text.find(quote, begin + 1);
  if (end == std::string_view::npos) return {};
  return text.substr(begin + 1, end - begin - 1);
}

// One of tinyobjloader's warnings in tessera's words (the ones a file can reach); any other is
// passed on with its values elided.
std::string inOwnWords(const std::string& line) {
  const std::string at_line = numberAfter(line, "line ");
  const std::string where = at_line.empty() ? "" : "line " + at_line + ": ";
  if (line.starts_with("material [")) {
    std::string name(between(line, '\''));
    if (name.empty()) name = trimmed(std::string_view(line).substr(10, line.find(']') - 10));
    return "usemtl '" + elided(name) + "': no such material in the MTL files; the default is used";
  }
  if (line.starts_with("Both `d` and `Tr`"))
    return "material '" + elided(between(line, '"')) + "' sets both d and Tr; d is used";
  if (line.starts_with("Empty group name")) return where + "a group without a name";
  if (line.starts_with("Looks like empty filename for mtllib"))
    return where + "an mtllib line names no file";
  if (line.starts_with("Failed parse `l'") || line.starts_with("Failed parse `p'"))
    return where + "a line or point element with a zero or unreadable index is skipped";
  return elided(line);
}

}  // namespace

// Passes tinyobjloader's warnings on, except those this loader reports better itself.
void forwardLibraryWarnings(const std::string& file, const std::string& text,
                            std::vector<std::string>& warnings) {
  static constexpr std::string_view kReplaced[] = {
      "Degenerated face",        "Vertex indices out of bounds", "Vertex normal indices",
      "Vertex texcoord indices", "Failed to load material",      "Material file",
  };
  std::set<std::string> seen;
  size_t skipped = 0;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = std::min(text.find('\n', begin), text.size());
    std::string line = trimmed(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    // "Degenerated face found\n." leaves a '.' at the start of the next message.
    line.erase(0, line.find_first_not_of(". "));
    if (line.empty()) continue;
    bool replaced = std::any_of(std::begin(kReplaced), std::end(kReplaced),
                                [&](std::string_view prefix) { return line.starts_with(prefix); });
    if (replaced || !seen.insert(line).second) continue;
    if (seen.size() > kMaxLibraryWarnings) {
      ++skipped;
      continue;
    }
    warnings.push_back(file + ": " + inOwnWords(line));
  }
  if (skipped > 0)
    warnings.push_back(file + ": " + std::to_string(skipped) + " more warnings like these");
}

// ---- Material libraries ----

bool FolderMaterialReader::operator()(const std::string& /*tinyobj_name*/,
                                      std::vector<tinyobj::material_t>* materials,
                                      std::map<std::string, int>* material_map,
                                      std::string* /*warn*/, std::string* /*err*/) {
  if (done_) return true;
  done_ = true;
  // Each library once, however often it is named: a file cannot make us parse one repeatedly.
  std::set<fs::path> seen;
  for (const std::string& text : libraries_)
    for (const std::string& name : libraryNames(text)) load(name, materials, material_map, seen);
  return true;
}

// The names on one `mtllib` line. Exporters write a name with spaces either as it is or with
// "\ "; a whole line that names an existing file is taken as one name.
std::vector<std::string> FolderMaterialReader::libraryNames(const std::string& text) const {
  std::string whole = trimmed(text);
  if (whole.empty()) return {};
  Expected<fs::path> as_one = resolveReferencedFile(folder_, whole);
  std::error_code error;
  if (as_one && fs::is_regular_file(*as_one, error)) return {whole};
  std::vector<std::string> names;
  std::string current;
  for (size_t i = 0; i < whole.size(); ++i) {
    if (whole[i] == '\\' && i + 1 < whole.size() && whole[i + 1] == ' ') {
      current += ' ';
      ++i;
    } else if (isBlank(whole[i])) {
      if (!current.empty()) names.push_back(std::move(current));
      current.clear();
    } else {
      current += whole[i];
    }
  }
  if (!current.empty()) names.push_back(std::move(current));
  return names;
}

void FolderMaterialReader::load(const std::string& name,
                                std::vector<tinyobj::material_t>* materials,
                                std::map<std::string, int>* material_map,
                                std::set<fs::path>& seen) {
  const std::string fallback = "; its materials fall back to the default";
  Expected<fs::path> path = resolveReferencedFile(folder_, name);
  if (!path) {
    warnings_.push_back(obj_name_ + ": material file '" + name +
                        "' refused: " + path.error().message + fallback);
    return;
  }
  if (!seen.insert(*path).second) return;
  const std::string path_name = path->string();
  Expected<std::vector<unsigned char>> bytes = readRegularFile(*path, kMaxMtlBytes, "MTL");
  if (!bytes) {
    warnings_.push_back(bytes.error().message + fallback);
    return;
  }
  std::stringstream stream(std::string(bytes->begin(), bytes->end()));
  const std::set<std::string> with_kd = materialsWithKd(stream);
  stream.clear();
  stream.seekg(0);
  std::string mtl_warnings, mtl_errors;
  const size_t first = materials->size();
  tinyobj::LoadMtl(material_map, materials, &stream, &mtl_warnings, &mtl_errors);
  for (size_t i = first; i < materials->size(); ++i)
    has_kd_.push_back(with_kd.contains((*materials)[i].name));
  forwardLibraryWarnings(path_name, mtl_warnings + mtl_errors, warnings_);
}

// ---- Materials ----

Material MaterialBuilder::build(const tinyobj::material_t& source, bool has_kd) {
  Material material;
  auto channel = [](float value, float fallback) {
    return std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : fallback;
  };
  // Kd is taken as linear, like a glTF base colour factor: MTL does not say, and it is the
  // value a renderer multiplies by. `d` (or 1 - `Tr`, tinyobjloader's reading) is alpha.
  float3 kd{channel(source.diffuse[0], 0.8f), channel(source.diffuse[1], 0.8f),
            channel(source.diffuse[2], 0.8f)};
  float alpha = channel(source.dissolve, 1.0f);
  if (!source.diffuse_texname.empty()) {
    if (!has_kd) kd = float3{1, 1, 1};
    const tinyobj::texture_option_t& options = source.diffuse_texopt;
    const bool srgb = !equalsIgnoreCase(options.colorspace, "linear");
    material.albedo = texture(source.diffuse_texname, srgb, source.name);
    material.sampler.wrap_s = material.sampler.wrap_t =
        options.clamp ? TextureWrap::kClamp : TextureWrap::kRepeat;
    bool moved = false;
    for (int i = 0; i < 3; ++i)
      moved |= options.origin_offset[i] != 0.0f || options.scale[i] != 1.0f;
    if (moved)
      warnings_.push_back(obj_name_ + ": material '" + source.name +
                          "': texture offset and scale (-o, -s) are not supported; ignored");
  }
  material.base_color = float4{kd, alpha};
  // A dissolve below 1 is a see-through material: glTF's alphaMode BLEND.
  if (alpha < 1.0f) material.alpha_mode = AlphaMode::kBlend;
  buildPbr(source, material);
  return material;
}

// MTL onto the metallic-roughness model (docs/formats.md): Pm metallic; Pr roughness, else from
// the Phong exponent Ns (alpha^2 = 2 / (Ns + 2), Walter et al.'s Blinn-Phong match; no specular
// Ks: rough); Ke (x map_Ke, sRGB) emission; norm, else map_Bump when it is an RGB image, the
// tangent-space normal map. Only --shading pbr reads these.
void MaterialBuilder::buildPbr(const tinyobj::material_t& source, Material& material) {
  auto finite = [](float value, float fallback) { return std::isfinite(value) ? value : fallback; };
  material.metallic = std::clamp(finite(source.metallic, 0.0f), 0.0f, 1.0f);
  const float ns = std::max(finite(source.shininess, 1.0f), 0.0f);
  const bool no_specular =
      source.specular[0] == 0.0f && source.specular[1] == 0.0f && source.specular[2] == 0.0f;
  material.roughness = no_specular ? 1.0f : std::sqrt(std::sqrt(2.0f / (ns + 2.0f)));
  if (source.roughness > 0.0f) material.roughness = std::min(finite(source.roughness, 1.0f), 1.0f);
  for (int i = 0; i < 3; ++i)
    material.emissive_factor[i] = std::max(finite(source.emission[i], 0.0f), 0.0f);
  if (!source.emissive_texname.empty()) {
    material.emissive.texture = texture(source.emissive_texname, /*srgb=*/true, source.name);
    if (material.emissive_factor.x == 0.0f && material.emissive_factor.y == 0.0f &&
        material.emissive_factor.z == 0.0f)
      material.emissive_factor = {1.0f, 1.0f, 1.0f};
  }
  const std::string& normal =
      !source.normal_texname.empty() ? source.normal_texname : source.bump_texname;
  if (normal.empty()) return;
  std::shared_ptr<const Texture> map = texture(normal, /*srgb=*/false, source.name);
  if (map && map->source_channels > 0 && map->source_channels < 3) {
    warnings_.push_back(obj_name_ + ": material '" + source.name + "': '" + normal +
                        "' is not an RGB image (a height map?); it is not used as a normal map");
    return;
  }
  material.normal.texture = map;
  material.normal_scale =
      source.normal_texname.empty() ? finite(source.bump_texopt.bump_multiplier, 1.0f) : 1.0f;
}

std::shared_ptr<const Texture> MaterialBuilder::texture(const std::string& reference, bool srgb,
                                                        const std::string& material_name) {
  const std::string dropped = "; material '" + material_name + "' is drawn without it";
  Expected<fs::path> path = resolveReferencedFile(folder_, reference);
  if (!path) {
    warnings_.push_back(obj_name_ + ": texture '" + reference +
                        "' refused: " + path.error().message + dropped);
    return nullptr;
  }
  auto key = std::make_pair(path->string(), srgb);
  if (auto cached = cache_.find(key); cached != cache_.end()) return cached->second;
  std::shared_ptr<const Texture>& slot = cache_[key];
  Expected<MaterialTexture> loaded = textures_.load(*path, srgb);
  if (!loaded) {
    if (!fatal_) fatal_ = loaded.error();
    return nullptr;
  }
  if (!loaded->texture) warnings_.push_back(loaded->warning + dropped);
  slot = loaded->texture;
  return slot;
}

}  // namespace tessera::io
