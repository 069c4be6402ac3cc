#include "load_budget.h"

#include <vector>

#include <tessera/io/image_loader.h>

#include "model_paths.h"

namespace tessera::io {

Error overBudget(const std::string& name, const std::string& what, uint64_t count,
                 uint64_t budget, const std::string& flag) {
  const std::string raise = flag.empty() ? "--memory-limit" : flag + " or --memory-limit";
  return makeError(name + ": " + std::to_string(count) + " " + what + ", over the budget of " +
                   std::to_string(budget) + "; raise it with " + raise);
}

Expected<void> checkBudget(const std::string& name, const std::string& what, uint64_t count,
                           uint64_t budget, const std::string& flag) {
  if (count > budget) return overBudget(name, what, count, budget, flag);
  return {};
}

Expected<MaterialTexture> TextureBudget::decode(const unsigned char* data, size_t size,
                                                const std::string& name, bool srgb) {
  Expected<ImageSize> header = readImageSize(data, size, name);
  if (!header) return MaterialTexture{nullptr, header.error().message};
  if (header->pixels() > budget_.texturePixels())
    return makeError(texturePixelsOverBudget(name, *header, budget_.texturePixels()));
  if (Expected<void> ok = checkBudget(name, "texture pixels in all of the model's textures",
                                      pixels_ + header->pixels(), budget_.totalTexturePixels(),
                                      "--max-texture-pixels");
      !ok)
    return ok.error();
  Expected<Texture> decoded = decodeTexture(data, size, name, srgb, budget_.texturePixels());
  if (!decoded) return MaterialTexture{nullptr, decoded.error().message};
  pixels_ += header->pixels();
  return MaterialTexture{std::make_shared<const Texture>(std::move(decoded).value()), {}};
}

Expected<MaterialTexture> TextureBudget::load(const std::filesystem::path& path, bool srgb) {
  Expected<std::vector<unsigned char>> bytes = readRegularFile(path, kMaxImageFileBytes, "image");
  if (!bytes) return MaterialTexture{nullptr, bytes.error().message};
  return decode(bytes->data(), bytes->size(), path.string(), srgb);
}

}  // namespace tessera::io
