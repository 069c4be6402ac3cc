// Resolve: shade each visible pixel of a tile once, encode sRGB, and write colour and the AOVs
// (triangle id, depth, normal) into the frame.
#pragma once

#include <vector>

#include <tessera/render/frame.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/raster.h"

namespace tessera::render {

void resolveTile(const TileVisibility& tile, const std::vector<TriangleChunk>& chunks,
                 const Scene& scene, Frame& frame);

}  // namespace tessera::render
