// libFuzzer target for the Radiance .hdr reader of environment lights (--hdri), straight from
// memory: an image it accepts holds only finite, non-negative radiance, as many texels as its
// size says.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <tessera/io/image_loader.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera;
  Expected<EnvironmentImage> image =
      io::decodeEnvironmentImage(data, size, "fuzz.hdr", /*max_pixels=*/1 << 20);
  if (!image) return 0;
  if (image->width < 2 || image->height < 1 ||
      image->texels.size() != static_cast<size_t>(image->width) * image->height)
    std::abort();
  // Each channel finite and non-negative (their sum may overflow: .hdr reaches 2^120).
  for (const float3& t : image->texels)
    if (!(t.x >= 0.0f && t.y >= 0.0f && t.z >= 0.0f) || !std::isfinite(t.x) ||
        !std::isfinite(t.y) || !std::isfinite(t.z))
      std::abort();
  return 0;
}
