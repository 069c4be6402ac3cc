// glTF materials, samplers and images as tessera materials, each built (and each image decoded)
// once, on first use. Private to tessera_io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

#include "gltf_nodes.h"
#include "load_budget.h"

namespace tinygltf {
class Model;
class Value;
struct Material;
}  // namespace tinygltf

namespace tessera::io::gltf {

class MaterialTable {
 public:
  // `warn` takes warnings about the model file, `warn_about` those that name their own file.
  MaterialTable(const tinygltf::Model& gltf, std::string name, std::filesystem::path folder,
                const LoadBudget& budget, Warn warn, Warn warn_about)
      : gltf_(gltf),
        name_(std::move(name)),
        folder_(std::move(folder)),
        warn_(std::move(warn)),
        warn_about_(std::move(warn_about)),
        textures_(budget) {}

  // The index in `materials` of a glTF material (-1: none), added there on first use. An error
  // when its texture is over the budget.
  Expected<uint16_t> materialFor(int gltf_material, std::vector<Material>& materials);

  // The sampler a textureInfo (baseColorTexture, normalTexture, ...: anything with index,
  // texCoord and extensions) reads its texture through: the texture's glTF sampler, the texCoord
  // and KHR_texture_transform (a warning, and the transform left out, when it holds other than
  // finite numbers). `label` names the map in warnings ("material 3 'metal' normalTexture").
  template <typename TextureInfo>
  Sampler readTextureInfoSampler(const TextureInfo& info, const std::string& label) {
    return textureInfoSampler(info.index, info.texCoord, info.extensions, label);
  }

 private:
  Sampler textureInfoSampler(int texture_index, int tex_coord,
                             const std::map<std::string, tinygltf::Value>& extensions,
                             const std::string& label);
  void readTextureTransform(const tinygltf::Value& extension, const std::string& label,
                            Sampler& sampler);
  Material buildMaterial(size_t index);
  Sampler sampler(size_t index);
  // `srgb`: colour (base colour, emissive) or data (the other maps): decoded once each way used.
  std::shared_ptr<const Texture> image(size_t index, const std::string& dropped, bool srgb = true);
  // A textureInfo's texture as a slot read through `sampler` (readTextureInfoSampler's: its own
  // set, wrap, filter and transform); empty, with a warning, when unusable.
  TextureSlot textureSlot(int index, const Sampler& sampler, bool srgb, const std::string& what);
  // metallicFactor ... alphaCutoff and their maps, each map on its own UV set, into `material`.
  void readPbr(const tinygltf::Material& source, const std::string& label, Material& material);

  const tinygltf::Model& gltf_;
  const std::string name_;
  const std::filesystem::path folder_;
  Warn warn_, warn_about_;
  std::map<int, uint16_t> material_index_;
  std::map<std::pair<size_t, bool>, std::shared_ptr<const Texture>> images_;  // (image, srgb)
  TextureBudget textures_;
  std::optional<Error> fatal_;  // a texture over the budget
};

}  // namespace tessera::io::gltf
