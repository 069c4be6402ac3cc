#include "render/resolve.h"

#include <algorithm>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tessera/scene/color.h>

namespace tessera::render {

void resolveTile(const TileVisibility& tile, const ShadedTile& shaded,
                 const std::vector<TriangleChunk>& chunks, Frame& frame) {
  const bool depth = !frame.depth.empty(), ids = !frame.triangle_id.empty(),
             normals = !frame.normal.empty();
  for (int ty = 0; ty < tile.height; ++ty) {
    const size_t row = static_cast<size_t>(tile.y0 + ty) * frame.width + tile.x0;
    const int t0 = ty * kTileSize;
    std::memcpy(&frame.color[row], &shaded.rgba[t0], sizeof(uint32_t) * tile.width);
    if (depth) std::memcpy(&frame.depth[row], &tile.depth[t0], sizeof(float) * tile.width);
    if (ids) {
      for (int tx = 0; tx < tile.width; ++tx) {
        const uint32_t key = tile.key[t0 + tx];
        frame.triangle_id[row + tx] =
            key == kEmptyKey ? kNoTriangle
                             : chunks[keyChunk(key)].shade[keyLocal(key)].triangle_id + 1;
      }
    }
    if (normals) {
      for (int tx = 0; tx < tile.width; ++tx)
        frame.normal[row + tx] = tile.key[t0 + tx] == kEmptyKey
                                     ? float3{}
                                     : float3{shaded.normal_x[t0 + tx], shaded.normal_y[t0 + tx],
                                              shaded.normal_z[t0 + tx]};
    }
  }
}

namespace {

// Fills n pixels with `value`, bypassing the cache where the row is long: nothing reads the
// background back before the frame is done.
void fillRow(uint32_t* out, size_t n, uint32_t value) {
#if defined(__SSE2__)
  // Whole cache lines streamed (four 16-byte stores each), the ends stored plainly.
  size_t i = 0;
  while (i < n && (reinterpret_cast<uintptr_t>(out + i) & 63) != 0) out[i++] = value;
  const __m128i v = _mm_set1_epi32(static_cast<int>(value));
  for (; i + 16 <= n; i += 16) {
    __m128i* line = reinterpret_cast<__m128i*>(out + i);
    _mm_stream_si128(line, v);
    _mm_stream_si128(line + 1, v);
    _mm_stream_si128(line + 2, v);
    _mm_stream_si128(line + 3, v);
  }
  for (; i < n; ++i) out[i] = value;
#else
  std::fill_n(out, n, value);
#endif
}

}  // namespace

void resolveEmptyTile(int x0, int y0, int width, int height, uint32_t background, Frame& frame) {
  const bool depth = !frame.depth.empty(), ids = !frame.triangle_id.empty(),
             normals = !frame.normal.empty();
  for (int y = y0; y < y0 + height; ++y) {
    const size_t row = static_cast<size_t>(y) * frame.width + x0;
    fillRow(&frame.color[row], static_cast<size_t>(width), background);
    if (depth) std::fill_n(&frame.depth[row], width, std::numeric_limits<float>::infinity());
    if (ids) std::fill_n(&frame.triangle_id[row], width, kNoTriangle);
    if (normals) std::fill_n(&frame.normal[row], width, float3{});
  }
#if defined(__SSE2__)
  _mm_sfence();  // the streamed stores are visible before the pool hands the frame back
#endif
}

}  // namespace tessera::render
