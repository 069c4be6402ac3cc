#include <tessera/render/composite.h>

#include <cmath>

#include <tessera/base/check.h>
#include <tessera/scene/color.h>
#include <tessera/scene/scene.h>

namespace tessera {

bool needsComposite(const Scene& scene, const RenderOptions& options) {
  return scene.background.w < 1.0f || options.opacity < 1.0f;
}

RenderOptions withCompositeInputs(const Scene& scene, const RenderOptions& options) {
  RenderOptions covered = options;
  if (needsComposite(scene, options)) covered.coverage = true;
  return covered;
}

void compositeOverBackground(float4 background, float opacity, Frame& frame) {
  TESSERA_CHECK(frame.coverage.size() == frame.pixelCount())
      << "compositing over the background reads the coverage AOV";
  const float* decode = srgbDecodeTable();
  const uint32_t bg_packed = packSrgba8(background);
  // The background as the resolve mixed it: its 8-bit code decoded.
  const float bg[3] = {decode[bg_packed & 0xff], decode[(bg_packed >> 8) & 0xff],
                       decode[(bg_packed >> 16) & 0xff]};
  const float bg_alpha = std::fmin(std::fmax(background.w, 0.0f), 1.0f);
  const size_t n = frame.pixelCount();
  for (size_t i = 0; i < n; ++i) {
    const uint8_t covered = frame.coverage[i];
    if (covered == 0) continue;  // the background as it was drawn
    const uint32_t c = frame.color[i];
    const float seen = opacity * (static_cast<float>(covered) / 255.0f);
    uint32_t out = 0;
    for (int k = 0; k < 3; ++k) {
      const float resolved = decode[(c >> (8 * k)) & 0xff];
      out |= static_cast<uint32_t>(encodeSrgb8(opacity * resolved + (1.0f - opacity) * bg[k]))
             << (8 * k);
    }
    const float alpha = seen + bg_alpha * (1.0f - seen);
    out |= static_cast<uint32_t>(std::lround(alpha * 255.0f)) << 24;
    frame.color[i] = out;
  }
}

void straightAlpha(std::span<uint32_t> pixels) {
  const float* decode = srgbDecodeTable();
  for (uint32_t& p : pixels) {
    const uint32_t a = p >> 24;
    if (a == 255) continue;
    if (a == 0) {
      p = 0;
      continue;
    }
    const float scale = 255.0f / static_cast<float>(a);
    uint32_t out = a << 24;
    for (int k = 0; k < 3; ++k)
      out |= static_cast<uint32_t>(encodeSrgb8(decode[(p >> (8 * k)) & 0xff] * scale)) << (8 * k);
    p = out;
  }
}

}  // namespace tessera
