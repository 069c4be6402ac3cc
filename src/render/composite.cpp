#include <tessera/render/composite.h>

#include <cmath>
#include <numbers>

#include <tessera/base/check.h>
#include <tessera/render/projection.h>
#include <tessera/scene/color.h>
#include <tessera/scene/scene.h>

#include "render/tone.h"

namespace tessera {

bool needsComposite(const Scene& scene, const RenderOptions& options) {
  return scene.background.w < 1.0f || options.opacity < 1.0f ||
         (scene.environment_background && scene.environment);
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

namespace {

// The environment's direction of camera-space direction d (the camera looks down -Z).
float3 environmentDirection(const float3x3& camera_to_environment, const double d[3]) {
  return normalize(camera_to_environment * float3{static_cast<float>(d[0]),
                                                  static_cast<float>(d[1]),
                                                  static_cast<float>(d[2])});
}

}  // namespace

void compositeEnvironment(const Scene& scene, const RenderOptions& options, Frame& frame) {
  if (!scene.environment_background || !scene.environment) return;
  TESSERA_CHECK(frame.coverage.size() == frame.pixelCount())
      << "compositing the environment reads the coverage AOV";
  const float3x3 camera_to_environment =
      scene.world_to_environment * inverse(upper3x3(scene.camera.view()));
  const double fov = static_cast<double>(scene.camera.fov_y_degrees) * std::numbers::pi / 180.0;
  const float* decode = srgbDecodeTable();
  const uint32_t bg_packed = packSrgba8(scene.background);
  const float3 bg{decode[bg_packed & 0xff], decode[(bg_packed >> 8) & 0xff],
                  decode[(bg_packed >> 16) & 0xff]};
  const EnvironmentImage& image = scene.environment->image();
  // The sky through the same display transform as the shaded surfaces.
  const render::ToneCurve tone = render::ToneCurve::of(scene);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const size_t i = static_cast<size_t>(y) * frame.width + x;
      const float behind = 1.0f - options.opacity * (frame.coverage[i] / 255.0f);
      if (behind <= 0.0f) continue;
      double d[3] = {0.0, 0.0, -1.0};
      if (!scene.camera.orthographic &&
          !rayDirection(options.projection, x + 0.5, y + 0.5, frame.width, frame.height, fov, d))
        continue;  // no ray (fisheye past 180 degrees): the plain background
      const float3 e = render::toneMap(
          tone, sampleEquirect(image, environmentDirection(camera_to_environment, d)));
      const uint32_t c = frame.color[i];
      uint32_t out = c & 0xff000000u;
      for (int k = 0; k < 3; ++k) {
        const float resolved = decode[(c >> (8 * k)) & 0xff];
        out |= static_cast<uint32_t>(encodeSrgb8(resolved + behind * (e[k] - bg[k]))) << (8 * k);
      }
      frame.color[i] = out;
    }
}

void compositeFrame(const Scene& scene, const RenderOptions& options, Frame& frame) {
  if (!needsComposite(scene, options)) return;
  compositeOverBackground(scene.background, options.opacity, frame);
  compositeEnvironment(scene, options, frame);
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
