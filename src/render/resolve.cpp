#include "render/resolve.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tessera/scene/color.h>

namespace tessera::render {

namespace {

// Streaming stores go only to whole 64-byte cache lines: a line written in part by them costs
// the memory a partial write, and a frame's rows need not start on a line (a std::vector's pixels
// start 16 bytes into one, and a tile's 64-pixel span then covers five lines, two of them in
// part). On a Xeon (Emerald Rapids) that made the streamed 4K cube frame take 13.1 ms against
// 6.3 ms written through the cache. The pixels before the first whole line and after the last go
// through the cache. Returns the [begin, end) pixel range of the whole lines within [0, n).
constexpr uintptr_t kLineBytes = 64;
std::pair<size_t, size_t> wholeLines(const uint32_t* out, size_t n) {
  const uintptr_t at = reinterpret_cast<uintptr_t>(out);
  const uintptr_t first = (at + kLineBytes - 1) & ~(kLineBytes - 1);
  const uintptr_t last = (at + n * sizeof(uint32_t)) & ~(kLineBytes - 1);
  if ((at & 3) != 0 || last <= first) return {0, 0};
  return {(first - at) / sizeof(uint32_t), (last - at) / sizeof(uint32_t)};
}

// Fills n pixels with `value`, bypassing the cache where `stream`: nothing reads the background
// back before the frame is done.
void fillRow(uint32_t* out, size_t n, uint32_t value, bool stream) {
#if defined(__SSE2__)
  const auto [begin, end] = stream ? wholeLines(out, n) : std::pair<size_t, size_t>{0, 0};
  if (begin == end) {
    std::fill_n(out, n, value);
    return;
  }
  std::fill_n(out, begin, value);
  const __m128i v = _mm_set1_epi32(static_cast<int>(value));
  for (size_t i = begin; i < end; i += 16) {
    __m128i* line = reinterpret_cast<__m128i*>(out + i);
    _mm_stream_si128(line, v);
    _mm_stream_si128(line + 1, v);
    _mm_stream_si128(line + 2, v);
    _mm_stream_si128(line + 3, v);
  }
  std::fill_n(out + end, n - end, value);
#else
  (void)stream;
  std::fill_n(out, n, value);
#endif
}

// Copies n pixels the same way: the frame is not read back while it is drawn.
void copyRow(uint32_t* out, const uint32_t* in, size_t n, bool stream) {
#if defined(__SSE2__)
  const auto [begin, end] = stream ? wholeLines(out, n) : std::pair<size_t, size_t>{0, 0};
  if (begin == end) {
    std::memcpy(out, in, n * sizeof(uint32_t));
    return;
  }
  std::memcpy(out, in, begin * sizeof(uint32_t));
  for (size_t i = begin; i < end; i += 16) {
    __m128i* line = reinterpret_cast<__m128i*>(out + i);
    const __m128i* from = reinterpret_cast<const __m128i*>(in + i);
    _mm_stream_si128(line, _mm_loadu_si128(from));
    _mm_stream_si128(line + 1, _mm_loadu_si128(from + 1));
    _mm_stream_si128(line + 2, _mm_loadu_si128(from + 2));
    _mm_stream_si128(line + 3, _mm_loadu_si128(from + 3));
  }
  std::memcpy(out + end, in + end, (n - end) * sizeof(uint32_t));
#else
  (void)stream;
  std::memcpy(out, in, n * sizeof(uint32_t));
#endif
}

// The streamed stores are visible before the pool hands the frame back.
void fenceStreams() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

// The size of cpu 0's last-level cache as Linux describes it (sysfs), 0 when it does not. Not
// sysconf: glibc's figure can be wrong in a VM (this project's gives 320 MB of L3 for 32 MB).
size_t lastLevelCacheBytes() {
  int best_level = 0;
  size_t best = 0;
  for (int index = 0; index < 16; ++index) {
    const std::string dir =
        "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index) + "/";
    std::ifstream level_file(dir + "level"), size_file(dir + "size"), type_file(dir + "type");
    int level = 0;
    std::string size, type;
    if (!(level_file >> level) || !(size_file >> size) || !(type_file >> type)) continue;
    if (type == "Instruction" || level <= best_level) continue;
    size_t value = 0, at = 0;
    while (at < size.size() && size[at] >= '0' && size[at] <= '9')
      value = value * 10 + static_cast<size_t>(size[at++] - '0');
    const char unit = at < size.size() ? size[at] : ' ';
    value <<= unit == 'K' ? 10 : unit == 'M' ? 20 : unit == 'G' ? 30 : 0;
    best_level = level;
    best = value;
  }
  return best;
}

}  // namespace

bool streamsFrame(size_t pixels, size_t triangles) {
  static const size_t cache = lastLevelCacheBytes();
  const size_t limit = cache > 0 ? cache / 2 : kUnknownCacheFrameBytes;
  const size_t bytes =
      pixels * sizeof(uint32_t) + triangles * (sizeof(RasterTriangle) + sizeof(ShadeTriangle));
  return bytes > limit;
}

bool streamsBackground(size_t pixels, size_t triangles) {
  return pixels * sizeof(uint32_t) > kStreamedBackgroundBytes || streamsFrame(pixels, triangles);
}

void resolveTile(const TileVisibility& tile, const ShadedTile& shaded,
                 const std::vector<TriangleChunk>& chunks, bool stream, Frame& frame) {
  const bool depth = !frame.depth.empty(), ids = !frame.triangle_id.empty(),
             normals = !frame.normal.empty();
  for (int ty = 0; ty < tile.height; ++ty) {
    const size_t row = static_cast<size_t>(tile.y0 + ty) * frame.width + tile.x0;
    const int t0 = ty * kTileSize;
    if (!shaded.direct)
      copyRow(&frame.color[row], &shaded.rgba[t0], static_cast<size_t>(tile.width), stream);
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
  if (stream) fenceStreams();
}

void resolveCoverage(const TileVisibility& tile, const int32_t* covered, int samples,
                     Frame& frame) {
  for (int ty = 0; ty < tile.height; ++ty) {
    uint8_t* out = &frame.coverage[static_cast<size_t>(tile.y0 + ty) * frame.width + tile.x0];
    const int t0 = ty * kTileSize;
    for (int tx = 0; tx < tile.width; ++tx) {
      out[tx] = covered ? static_cast<uint8_t>((covered[t0 + tx] * 255 + samples / 2) / samples)
                        : (tile.key[t0 + tx] == kEmptyKey ? 0 : 255);
    }
  }
}

void resolveEmptyRun(const TileGrid& grid, const std::vector<uint8_t>& tile_empty, int tile,
                     uint32_t background, bool stream, Frame& frame) {
  const int tx = tile % grid.columns, ty = tile / grid.columns;
  const size_t index = static_cast<size_t>(tile);
  if (tx > 0 && tile_empty[index - 1]) return;
  int run_end = tx + 1;
  while (run_end < grid.columns && tile_empty[index + static_cast<size_t>(run_end - tx)]) ++run_end;
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  resolveEmptyTile(x0, y0, std::min(run_end * kTileSize, grid.width) - x0,
                   std::min(kTileSize, grid.height - y0), background, stream, frame);
}

void resolveEmptyTile(int x0, int y0, int width, int height, uint32_t background, bool stream,
                      Frame& frame) {
  const bool depth = !frame.depth.empty(), ids = !frame.triangle_id.empty(),
             normals = !frame.normal.empty(), coverage = !frame.coverage.empty();
  for (int y = y0; y < y0 + height; ++y) {
    const size_t row = static_cast<size_t>(y) * frame.width + x0;
    fillRow(&frame.color[row], static_cast<size_t>(width), background, stream);
    if (depth) std::fill_n(&frame.depth[row], width, std::numeric_limits<float>::infinity());
    if (ids) std::fill_n(&frame.triangle_id[row], width, kNoTriangle);
    if (normals) std::fill_n(&frame.normal[row], width, float3{});
    if (coverage) std::fill_n(&frame.coverage[row], width, uint8_t{0});
  }
  if (stream) fenceStreams();
}

}  // namespace tessera::render
