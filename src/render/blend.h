// alphaMode BLEND: the transparent pass after the opaque one.
//
// Setup leaves blended triangles out of the tile bins (TriangleChunk::blended), so the opaque
// raster, shading and resolve never see them. BlendOrder then puts them in back-to-front order,
// per object and per triangle: objects by the mean depth of their blended triangles, farthest
// first; within an object its triangles by their depth, farthest first; ties in submission order
// (the chunks' records read in order, whatever the chunk layout). It bins them in that order, and
// after a tile is resolved the blend kernel (blend_kernel.h) draws the tile's share one triangle
// after the other: each pixel, or each sample with MSAA, that the triangle covers in front of the
// opaque depth there (the depth test without the write) takes colour C with alpha A over what it
// holds, in linear light: C A + D (1 - A). The opaque depth and the AOVs (ids, depth, normals)
// stay the opaque surface's; the coverage AOV, the matte that --no-background writes, becomes
// A + c (1 - A), so a glass over nothing is as transparent in the PNG as it looks.
//
// The image is bit-identical for any worker count: the order is a total one over the submission
// sequence, each tile is drawn by one worker, and the blend itself is scalar code compiled once.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/vec.h>
#include <tessera/render/frame.h>
#include <tessera/scene/scene.h>

#include "render/bin.h"
#include "render/msaa.h"
#include "render/vertex.h"

namespace tessera::render {

// Whether a record of this material is drawn by the transparent pass.
inline bool isBlended(const Material& material) {
  return material.alpha_mode == AlphaMode::kBlend;
}

// The depth by which the transparent pass orders a record: its window depth at the centre of its
// pixel box, from its depth plane (a number that orders triangles as their distance does, clipped
// pieces included). Not below 0 (a NaN counts as 0), so that the sort's comparisons are a strict
// order.
float blendRecordDepth(const RasterTriangle& t);

// One blended record in the back-to-front sort.
struct BlendEntry {
  float object_depth;  // the mean of the object's, farthest first
  float depth;         // the record's (blendRecordDepth), farthest first
  uint32_t object;     // index into the frame's objects
  uint32_t key;        // submission order breaks ties
};

// The back-to-front order of BlendOrder, for `entries` given in submission order (object indices
// below `object_count`): sets each entry's object_depth to the mean of its object's depths (summed
// in double, in the given order) and sorts. The Vulkan backends order their blended triangles with
// it, so their drawing order is the CPU's. The scratch vectors only grow.
void sortBlendEntries(std::vector<BlendEntry>& entries, size_t object_count,
                      std::vector<double>& object_sum, std::vector<uint32_t>& object_entries);

class BlendOrder {
 public:
  // Orders the blended records of chunks [0, chunk_count) and bins them (keys: raster.h's
  // makeKey). The buffers only grow.
  void build(const std::vector<TriangleChunk>& chunks, size_t chunk_count,
             const std::vector<ObjectTransforms>& objects, const TileGrid& grid);

  bool empty() const { return order_.empty(); }
  const ChunkBins& bins() const { return bins_; }
  // The keys in drawing order (tests).
  size_t size() const { return order_.size(); }
  uint32_t keyAt(size_t i) const { return order_[i].key; }

 private:
  std::vector<BlendEntry> order_;
  std::vector<double> object_sum_;
  std::vector<uint32_t> object_count_;
  ChunkBins bins_;
};

// One worker's transparent layer of a tile: the colour of every sample of the pixels a blended
// triangle touched (linear light), and their coverage. A pixel starts, when first touched, with
// every sample at the resolved pixel's colour and coverage (the frame's): the over operator is
// affine in what lies behind, so this is exact wherever a blended triangle covers all of a
// pixel's samples, and within one resolve step elsewhere.
class BlendTile {
 public:
  // The tile of `frame` whose first pixel is (x0, y0), `samples` per pixel. The frame's coverage
  // AOV, where it has one, is updated with its colours.
  void begin(int x0, int y0, int samples, Frame& frame);
  // Colour `color` at alpha `alpha` over the samples of tile pixel `pixel` (y * kTileSize + x)
  // set in `sample_mask`.
  void over(int pixel, uint32_t sample_mask, float3 color, float alpha);
  // Writes the touched pixels back into the frame: their samples' mean, encoded to sRGB.
  void finish();

 private:
  void touch(int pixel);

  int x0_ = 0, y0_ = 0, samples_ = 1;
  Frame* frame_ = nullptr;
  std::vector<uint8_t> touched_;  // per tile pixel
  std::vector<int> touched_list_;
  std::vector<float> color_;     // per pixel, per sample: r, g, b
  std::vector<float> coverage_;  // per pixel, per sample
};

}  // namespace tessera::render
