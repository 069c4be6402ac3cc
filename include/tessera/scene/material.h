// Materials, and the list an object draws with: shared between the instances of one mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <vector>

#include <tessera/math/vec.h>
#include <tessera/scene/texture.h>

namespace tessera {

// glTF's alphaMode: opaque, cut at alpha_cutoff, or blended over what lies behind.
enum class AlphaMode : uint8_t { kOpaque, kMask, kBlend };

// A texture of a material (null: none) with the sampler it is read through.
struct TextureSlot {
  std::shared_ptr<const Texture> texture;
  Sampler sampler;
  explicit operator bool() const { return texture != nullptr; }
};

// glTF 2.0's metallic-roughness material (and what OBJ's MTL maps onto it, docs/formats.md). The
// Lambert shading modes read base_color and albedo only; Shading::kPbr reads all of it.
struct Material {
  float4 base_color{0.8f, 0.8f, 0.8f, 1.0f};  // linear RGBA
  std::shared_ptr<const Texture> albedo;      // optional; multiplies base_color (sRGB texels)
  Sampler sampler;                            // albedo's
  float metallic = 0.0f;   // glTF's default is 1; a material that says nothing is a dielectric
  float roughness = 1.0f;  // perceptual roughness (alpha = roughness^2)
  TextureSlot metallic_roughness;  // linear; G = roughness, B = metallic, multiplying the factors
  TextureSlot normal;              // tangent space, linear; normal_scale scales its X and Y
  float normal_scale = 1.0f;
  TextureSlot occlusion;  // linear; R, mixed by occlusion_strength
  float occlusion_strength = 1.0f;
  TextureSlot emissive;                      // sRGB; multiplies emissive_factor
  float3 emissive_factor{0.0f, 0.0f, 0.0f};  // linear
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;
  // Both faces are meant to be seen (glTF `doubleSided`). The renderer culls per Object
  // (Object::cull); a caller chooses that from its materials (io::Model::cull_back_faces).
  bool double_sided = false;
  // A simulation's property of the material (the density diagnostic, `--aov density`); the
  // renderer's shading does not read it.
  float density = 1.0f;
};

// Whether any texture of `m` (its albedo or a PBR map) is read through TEXCOORD_1.
inline bool readsTexcoord1(const Material& m) {
  auto reads = [](const std::shared_ptr<const Texture>& texture, const Sampler& sampler) {
    return texture != nullptr && sampler.texcoord == 1;
  };
  return reads(m.albedo, m.sampler) ||
         reads(m.metallic_roughness.texture, m.metallic_roughness.sampler) ||
         reads(m.normal.texture, m.normal.sampler) ||
         reads(m.occlusion.texture, m.occlusion.sampler) ||
         reads(m.emissive.texture, m.emissive.sampler);
}

// A vector of materials whose copies share one array until one of them is changed (copy on
// write): 10,000 instances of a mesh hold one list, not 10,000. Reads are as for a const
// std::vector; a non-const access detaches the list first. Like std::vector, a list is not to be
// changed while another thread reads it.
class MaterialList {
 public:
  MaterialList() : items_(std::make_shared<std::vector<Material>>()) {}
  MaterialList(std::initializer_list<Material> items)
      : items_(std::make_shared<std::vector<Material>>(items)) {}
  MaterialList(std::vector<Material> items)  // NOLINT: implicit, as a vector assigns
      : items_(std::make_shared<std::vector<Material>>(std::move(items))) {}
  MaterialList& operator=(std::vector<Material> items) {
    items_ = std::make_shared<std::vector<Material>>(std::move(items));
    return *this;
  }
  MaterialList& operator=(std::initializer_list<Material> items) {
    items_ = std::make_shared<std::vector<Material>>(items);
    return *this;
  }

  size_t size() const { return items_->size(); }
  bool empty() const { return items_->empty(); }
  const Material& operator[](size_t i) const { return (*items_)[i]; }
  const Material& at(size_t i) const { return items_->at(i); }
  const Material& front() const { return items_->front(); }
  const Material& back() const { return items_->back(); }
  const Material* data() const { return items_->data(); }
  std::vector<Material>::const_iterator begin() const { return items_->cbegin(); }
  std::vector<Material>::const_iterator end() const { return items_->cend(); }
  const std::vector<Material>& vector() const { return *items_; }
  operator const std::vector<Material>&() const { return *items_; }  // NOLINT

  // Changing access: the list is copied first when another holder shares it.
  Material& operator[](size_t i) { return own()[i]; }
  Material& at(size_t i) { return own().at(i); }
  Material& front() { return own().front(); }
  Material& back() { return own().back(); }
  std::vector<Material>::iterator begin() { return own().begin(); }
  std::vector<Material>::iterator end() { return own().end(); }
  void push_back(Material m) { own().push_back(std::move(m)); }
  void clear() { own().clear(); }
  void resize(size_t n) { own().resize(n); }
  // Whether `other` holds the same array (not a copy of it).
  bool sharesWith(const MaterialList& other) const { return items_ == other.items_; }

 private:
  std::vector<Material>& own() {
    if (items_.use_count() > 1) items_ = std::make_shared<std::vector<Material>>(*items_);
    return *items_;
  }
  std::shared_ptr<std::vector<Material>> items_;
};

}  // namespace tessera
