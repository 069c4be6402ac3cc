// The budget checks the loaders share (LoadBudget in model_loader.h). Private to tessera_io.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <tessera/base/expected.h>
#include <tessera/io/model_loader.h>
#include <tessera/scene/texture.h>

namespace tessera::io {

// "NAME: the model has 20000000 triangles (after instancing), over the budget of 16777216;
// raise it with --max-triangles or --memory-limit". `what` is "triangles (after instancing)".
Error overBudget(const std::string& name, const std::string& what, uint64_t count,
                 uint64_t budget, const std::string& flag);

// Checks a count against its budget: `flag` names the flag that raises it besides
// --memory-limit ("--max-triangles"), or is empty when only the memory limit does.
Expected<void> checkBudget(const std::string& name, const std::string& what, uint64_t count,
                           uint64_t budget, const std::string& flag);

// A texture for a material, or why the material goes without one.
struct MaterialTexture {
  std::shared_ptr<const Texture> texture;  // null: see warning
  std::string warning;
};

// Decodes a model's textures within the budget: each within LoadBudget::texturePixels(), all
// together within totalTexturePixels(), checked from the image's header before it is decoded.
// Over budget is an error (the model fails to load); an unreadable image is a warning.
class TextureBudget {
 public:
  explicit TextureBudget(const LoadBudget& budget) : budget_(budget) {}

  Expected<MaterialTexture> decode(const unsigned char* data, size_t size,
                                   const std::string& name, bool srgb);
  Expected<MaterialTexture> load(const std::filesystem::path& path, bool srgb);

 private:
  LoadBudget budget_;
  uint64_t pixels_ = 0;
};

}  // namespace tessera::io
