#include <tessera/render/accumulate.h>

#include <algorithm>
#include <cmath>

#include <tessera/base/check.h>
#include <tessera/scene/color.h>

namespace tessera {

namespace {

// Adds a frame's colours, decoded to linear light, and its alpha to the running sum.
void addLinear(const Frame& frame, std::vector<float>& sum) {
  const float* decode = srgbDecodeTable();
  const size_t n = frame.pixelCount();
  for (size_t i = 0; i < n; ++i) {
    const uint32_t c = frame.color[i];
    sum[4 * i] += decode[c & 0xff];
    sum[4 * i + 1] += decode[(c >> 8) & 0xff];
    sum[4 * i + 2] += decode[(c >> 16) & 0xff];
    sum[4 * i + 3] += static_cast<float>(c >> 24);
  }
}

}  // namespace

Expected<void> Accumulator::render(Backend& backend, const Scene& scene,
                                   const RenderOptions& options, int samples, Frame& out) {
  TESSERA_CHECK(samples >= 1) << "an accumulation takes at least one frame, not " << samples;
  RenderOptions first = options;
  first.jitter = jitterOffset(0);
  backend.render(scene, first, out);
  if (auto result = backend.lastResult(); !result) return result;
  if (samples == 1) return {};

  sum_.assign(out.pixelCount() * 4, 0.0f);
  addLinear(out, sum_);
  RenderOptions jittered = options;
  jittered.depth = jittered.ids = jittered.normals = jittered.coverage = false;
  for (int i = 1; i < samples; ++i) {
    jittered.jitter = jitterOffset(static_cast<uint32_t>(i));
    backend.render(scene, jittered, scratch_);
    if (auto result = backend.lastResult(); !result) return result;
    addLinear(scratch_, sum_);
  }
  const float scale = 1.0f / static_cast<float>(samples);
  // Alpha averages too (a transparent background's edges); colours premultiplied by it stay so.
  for (size_t i = 0; i < out.pixelCount(); ++i) {
    const uint32_t alpha = static_cast<uint32_t>(std::lround(sum_[4 * i + 3] * scale));
    out.color[i] = encodeSrgb8(sum_[4 * i] * scale) |
                   static_cast<uint32_t>(encodeSrgb8(sum_[4 * i + 1] * scale)) << 8 |
                   static_cast<uint32_t>(encodeSrgb8(sum_[4 * i + 2] * scale)) << 16 |
                   std::min(alpha, 255u) << 24;
  }
  return {};
}

}  // namespace tessera
