// vulkan-raster's transparent pass (alphaMode BLEND): the blended triangles, in the CPU's
// back-to-front order (blend_order.h), drawn after the opaque ones into the linear colour
// (RGBA16F: the blend happens in linear light) with the over operator, the depth test against the
// opaque depth and no depth write. Their indices are appended after the scene's, in drawing order
// (one run of triangles per object, since the CPU orders whole objects), and the scene's own
// copies are made degenerate, so that no opaque draw, and no AOV, sees a blended triangle.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/render/options.h>
#include <tessera/scene/scene.h>

#include "vulkan/blend_order.h"
#include "vulkan/scene_upload.h"

namespace tessera::vulkan {

// A draw of the transparent pass: triangles [first, first + count) of the appended range, all of
// object `object`.
struct RasterBlendRun {
  uint32_t object, first, count;
};

class RasterBlendDraws {
 public:
  // Orders the scene's blended triangles and rewrites `packed` as above (it must come from
  // packScene with IndexPolicy::kDegenerateDropped). False when there are none.
  bool prepare(const Scene& scene, const RenderOptions& options, PackedScene& packed);
  const std::vector<RasterBlendRun>& runs() const { return runs_; }

 private:
  BlendDrawOrder order_;
  std::vector<RasterBlendRun> runs_;
  std::vector<uint8_t> drawn_;  // per scene triangle: appended already (a clipped one's pieces)
};

}  // namespace tessera::vulkan
