#include "gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <system_error>

#include <tessera/io/image_loader.h>

#include "gltf_accessors.h"
#include "gltf_transforms.h"
#include "load_budget.h"
#include "model_paths.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace fs = std::filesystem;

namespace {

// Mesh::triangle_materials holds uint16_t.
constexpr size_t kMaxMaterials = size_t{1} << 16;

}  // namespace

Expected<uint16_t> MaterialTable::materialFor(int gltf_material, std::vector<Material>& materials) {
  if (gltf_material >= 0 && static_cast<size_t>(gltf_material) >= gltf_.materials.size()) {
    warn_("a primitive refers to material " + std::to_string(gltf_material) +
          ", which does not exist; the default material is used");
    gltf_material = -1;
  }
  auto found = material_index_.find(gltf_material);
  if (found != material_index_.end()) return found->second;
  if (materials.size() == kMaxMaterials)
    return makeError(name_ + ": more than " + std::to_string(kMaxMaterials) + " materials in use");
  const auto index = static_cast<uint16_t>(materials.size());
  Material material =
      gltf_material < 0 ? Material{} : buildMaterial(static_cast<size_t>(gltf_material));
  if (fatal_) return *fatal_;
  materials.push_back(std::move(material));
  material_index_.emplace(gltf_material, index);
  return index;
}

Material MaterialTable::buildMaterial(size_t index) {
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
    warn_(label + ": a baseColorFactor that is not 4 numbers is ignored");
  }
  const tinygltf::TextureInfo& info = source.pbrMetallicRoughness.baseColorTexture;
  const Sampler base_sampler =
      info.index >= 0 ? readTextureInfoSampler(info, label + " baseColorTexture") : Sampler{};
  readPbr(source, label, material);
  if (info.index >= 0) {
    const std::string dropped = "; " + label + " is drawn without its texture";
    if (static_cast<size_t>(info.index) >= gltf_.textures.size()) {
      warn_(label + " uses texture " + std::to_string(info.index) + ", which does not exist" +
            dropped);
      return material;
    }
    const tinygltf::Texture& texture = gltf_.textures[static_cast<size_t>(info.index)];
    if (texture.source < 0 || static_cast<size_t>(texture.source) >= gltf_.images.size()) {
      warn_("texture " + std::to_string(info.index) + " has no usable image" + dropped);
      return material;
    }
    material.albedo = image(static_cast<size_t>(texture.source), dropped);
    material.sampler = base_sampler;
  }
  return material;
}

Sampler MaterialTable::textureInfoSampler(int texture_index, int tex_coord,
                                          const tinygltf::ExtensionMap& extensions,
                                          const std::string& label) {
  Sampler sampler;
  if (texture_index >= 0 && static_cast<size_t>(texture_index) < gltf_.textures.size()) {
    const int index = gltf_.textures[static_cast<size_t>(texture_index)].sampler;
    if (index >= 0 && static_cast<size_t>(index) < gltf_.samplers.size())
      sampler = this->sampler(static_cast<size_t>(index));
    else if (index >= 0)
      warn_("texture " + std::to_string(texture_index) + " refers to sampler " +
            std::to_string(index) + ", which does not exist; the default is used");
  }
  sampler.texcoord = tex_coord;
  const auto found = extensions.find("KHR_texture_transform");
  if (found != extensions.end()) readTextureTransform(found->second, label, sampler);
  // Meshes keep TEXCOORD_0 and TEXCOORD_1 (Mesh::uvs, uvs1).
  if (sampler.texcoord < 0 || sampler.texcoord > 1) {
    warn_(label + ": texCoord " + std::to_string(sampler.texcoord) +
          (sampler.texcoord < 0 ? " is not a set" : " is past the two sets tessera reads") +
          "; TEXCOORD_0 is used");
    sampler.texcoord = 0;
  }
  return sampler;
}

void MaterialTable::readTextureTransform(const tinygltf::Value& extension, const std::string& label,
                                         Sampler& sampler) {
  const std::string where = label + ": KHR_texture_transform";
  if (!extension.IsObject()) {
    warn_(where + " is not an object; the texture is drawn without it");
    return;
  }
  bool sound = true;
  // Numbers as floats; a missing member keeps its default, anything else makes it unsound.
  auto number = [&](const tinygltf::Value& value, float& out) {
    if (!value.IsNumber()) {
      sound = false;
      return;
    }
    out = static_cast<float>(value.GetNumberAsDouble());
  };
  auto pair = [&](const char* name, float2& out) {
    if (!extension.Has(name)) return;
    const tinygltf::Value& value = extension.Get(name);
    if (!value.IsArray() || value.ArrayLen() != 2) {
      sound = false;
      return;
    }
    number(value.Get(0), out.x);
    number(value.Get(1), out.y);
  };
  TextureTransform transform;
  pair("offset", transform.offset);
  pair("scale", transform.scale);
  if (extension.Has("rotation")) number(extension.Get("rotation"), transform.rotation);
  if (!sound || !transform.finite()) {
    warn_(where +
          " holds something other than finite numbers (offset and scale: two each, "
          "rotation: one); the texture is drawn without the transform");
  } else {
    sampler.transform = transform;
  }
  if (extension.Has("texCoord")) {
    const tinygltf::Value& value = extension.Get("texCoord");
    if (value.IsNumber() && value.GetNumberAsDouble() >= 0.0 && value.GetNumberAsDouble() < 65536.0)
      sampler.texcoord = value.GetNumberAsInt();
    else
      warn_(where + ": texCoord is not a set number; the textureInfo's is used");
  }
}

namespace {

// A factor from the file: finite and within [lo, hi], else the glTF default with a warning.
float readFactor(double value, double lo, double hi, float fallback, const std::string& what,
                 const Warn& warn) {
  if (std::isfinite(value) && value >= lo && value <= hi) return toFloat(value);
  warn(what + " " + std::to_string(value) + " is outside [" + std::to_string(lo) + ", " +
       std::to_string(hi) + "]; the default " + std::to_string(fallback) + " is used");
  return fallback;
}

}  // namespace

TextureSlot MaterialTable::textureSlot(int index, const Sampler& sampler, bool srgb,
                                       const std::string& what) {
  TextureSlot slot;
  if (index < 0) return slot;
  const std::string dropped = "; " + what + " is left out";
  if (static_cast<size_t>(index) >= gltf_.textures.size()) {
    warn_(what + " uses texture " + std::to_string(index) + ", which does not exist" + dropped);
    return slot;
  }
  const tinygltf::Texture& texture = gltf_.textures[static_cast<size_t>(index)];
  if (texture.source < 0 || static_cast<size_t>(texture.source) >= gltf_.images.size()) {
    warn_("texture " + std::to_string(index) + " has no usable image" + dropped);
    return slot;
  }
  slot.texture = image(static_cast<size_t>(texture.source), dropped, srgb);
  slot.sampler = sampler;
  return slot;
}

void MaterialTable::readPbr(const tinygltf::Material& source, const std::string& label,
                            Material& material) {
  const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
  auto slot = [&](const auto& info, bool srgb, const std::string& what) {
    return textureSlot(info.index, readTextureInfoSampler(info, what), srgb, what);
  };
  material.metallic =
      readFactor(pbr.metallicFactor, 0.0, 1.0, 1.0f, label + ": metallicFactor", warn_);
  material.roughness =
      readFactor(pbr.roughnessFactor, 0.0, 1.0, 1.0f, label + ": roughnessFactor", warn_);
  material.metallic_roughness =
      slot(pbr.metallicRoughnessTexture, false, label + "'s metallicRoughnessTexture");
  material.normal = slot(source.normalTexture, false, label + "'s normalTexture");
  if (material.normal && material.normal.texture->source_channels > 0 &&
      material.normal.texture->source_channels < 3) {
    warn_(label + "'s normalTexture is not an RGB image (" +
          std::to_string(material.normal.texture->source_channels) + " channels); it is left out");
    material.normal = {};
  }
  material.normal_scale = readFactor(source.normalTexture.scale, -1e6, 1e6, 1.0f,
                                     label + ": normalTexture.scale", warn_);
  material.occlusion = slot(source.occlusionTexture, false, label + "'s occlusionTexture");
  material.occlusion_strength = readFactor(source.occlusionTexture.strength, 0.0, 1.0, 1.0f,
                                           label + ": occlusionTexture.strength", warn_);
  material.emissive = slot(source.emissiveTexture, true, label + "'s emissiveTexture");
  if (source.emissiveFactor.size() == 3) {
    for (int i = 0; i < 3; ++i)
      material.emissive_factor[i] = readFactor(source.emissiveFactor[static_cast<size_t>(i)], 0.0,
                                               1e6, 0.0f, label + ": emissiveFactor", warn_);
  } else if (!source.emissiveFactor.empty()) {
    warn_(label + ": an emissiveFactor that is not 3 numbers is ignored");
  }
  if (source.alphaMode == "MASK") {
    material.alpha_mode = AlphaMode::kMask;
  } else if (source.alphaMode == "BLEND") {
    material.alpha_mode = AlphaMode::kBlend;
  } else if (source.alphaMode != "OPAQUE" && !source.alphaMode.empty()) {
    warn_(label + ": unknown alphaMode '" + source.alphaMode + "'; drawn opaque");
  }
  material.alpha_cutoff =
      readFactor(source.alphaCutoff, 0.0, 1e6, 0.5f, label + ": alphaCutoff", warn_);
}

Sampler MaterialTable::sampler(size_t index) {
  const tinygltf::Sampler& source = gltf_.samplers[index];
  Sampler sampler;
  // One filter for magnification and minification: the magnification filter says nearest or
  // linear (without one, the minification filter's base does); linear is trilinear where
  // minification uses mipmaps or is left to tessera.
  const int mag = source.magFilter, min = source.minFilter;
  const bool min_nearest = min == TINYGLTF_TEXTURE_FILTER_NEAREST ||
                           min == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                           min == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
  const bool mipmapped =
      min < 0 || (min != TINYGLTF_TEXTURE_FILTER_NEAREST && min != TINYGLTF_TEXTURE_FILTER_LINEAR);
  if (mag >= 0 ? mag == TINYGLTF_TEXTURE_FILTER_NEAREST : min_nearest)
    sampler.filter = TextureFilter::kNearest;
  else
    sampler.filter = mipmapped ? TextureFilter::kTrilinear : TextureFilter::kBilinear;
  auto wrap = [](int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClamp;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirroredRepeat;
    return TextureWrap::kRepeat;
  };
  sampler.wrap_s = wrap(source.wrapS);
  sampler.wrap_t = wrap(source.wrapT);
  return sampler;
}

std::shared_ptr<const Texture> MaterialTable::image(size_t index, const std::string& dropped,
                                                    bool srgb) {
  auto cached = images_.find({index, srgb});
  if (cached != images_.end()) return cached->second;
  std::shared_ptr<const Texture>& slot = images_[{index, srgb}];
  const tinygltf::Image& source = gltf_.images[index];
  const std::string label = name_ + " image " + std::to_string(index);
  Expected<MaterialTexture> decoded = MaterialTexture{nullptr, label + ": no image data"};
  if (source.bufferView >= 0) {
    Expected<std::span<const uint8_t>> bytes = viewBytes(gltf_, source.bufferView, label);
    if (!bytes) {
      warn_(bytes.error().message.substr(name_.size() + 1) + dropped);
      return nullptr;
    }
    decoded = textures_.decode(bytes->data(), bytes->size(), label, srgb);
  } else if (!source.image.empty()) {
    decoded = textures_.decode(source.image.data(), source.image.size(), label, srgb);
  } else if (!source.uri.empty()) {
    const std::string reference = percentDecoded(source.uri);
    if (folder_.empty()) {
      warn_("image " + std::to_string(index) + ": '" + elided(reference) +
            "' is an external file, and this model was given in memory" + dropped);
      return nullptr;
    }
    Expected<fs::path> path = resolveReferencedFile(folder_, reference);
    if (!path) {
      warn_("image " + std::to_string(index) + ": '" + elided(reference) +
            "' refused: " + path.error().message + dropped);
      return nullptr;
    }
    decoded = textures_.load(*path, srgb);
  }
  if (!decoded) {
    if (!fatal_) fatal_ = decoded.error();
    return nullptr;
  }
  if (!decoded->texture) warn_about_(decoded->warning + dropped);
  slot = decoded->texture;
  return slot;
}

}  // namespace tessera::io::gltf
