// Albedo textures: 8-bit RGBA texels; base colour textures hold sRGB-encoded values and are
// decoded to linear when sampled (the decode is exact: a 256-entry table).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include <tessera/base/huge_pages.h>
#include <tessera/math/vec.h>

namespace tessera {

// kTrilinear: bilinear in the two mip levels around the level of detail the pixel's screen-space
// UV footprint asks for, blended (falls back to kBilinear on a texture without mip levels).
enum class TextureFilter { kNearest, kBilinear, kTrilinear };
// Per axis, as OpenGL's REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT (the OpenGL 4.6 specification,
// table 8.20: texel i of a size-n axis reads (n - 1) - mirror((i mod 2n) - n) when mirrored).
enum class TextureWrap { kRepeat, kClamp, kMirroredRepeat };

// A 2x3 affine map of texture coordinates: uv' = (m00 u + m01 v + m02, m10 u + m11 v + m12).
struct UvAffine {
  float m00 = 1.0f, m01 = 0.0f, m02 = 0.0f;
  float m10 = 0.0f, m11 = 1.0f, m12 = 0.0f;
  // The same operations, in the same order, as the eight-lane shading path.
  float2 apply(float2 uv) const {
    return {(m00 * uv.x + m01 * uv.y) + m02, (m10 * uv.x + m11 * uv.y) + m12};
  }
};

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv, in the extension's
// convention (rotation in radians, counter-clockwise in UV space with v pointing down the image).
struct TextureTransform {
  float2 offset{0.0f, 0.0f};
  float rotation = 0.0f;
  float2 scale{1.0f, 1.0f};
  bool identity() const {
    return offset.x == 0.0f && offset.y == 0.0f && rotation == 0.0f && scale.x == 1.0f &&
           scale.y == 1.0f;
  }
  bool finite() const;
  // The transform in tessera's texture coordinates (v = 0 at the bottom row, where the
  // extension's v = 0 is the top row): uv' = affine().apply(uv).
  UvAffine affine() const;
};

// How a material reads one of its textures: glTF's sampler, and its textureInfo's texture
// coordinate set and transform.
struct Sampler {
  Sampler() = default;
  Sampler(TextureFilter f, TextureWrap s, TextureWrap t) : filter(f), wrap_s(s), wrap_t(t) {}
  Sampler(TextureFilter f, TextureWrap w) : Sampler(f, w, w) {}

  TextureFilter filter = TextureFilter::kTrilinear;
  TextureWrap wrap_s = TextureWrap::kRepeat;  // along u
  TextureWrap wrap_t = TextureWrap::kRepeat;  // along v
  TextureTransform transform;                 // identity unless the file says KHR_texture_transform
  int texcoord = 0;                           // TEXCOORD_<n>: 0 or 1 (Mesh::uvs, Mesh::uvs1)
};

struct TextureLevel {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> texels;  // RGBA8, R in the low byte, row 0 at the top
};

// The bilinear filter's arithmetic, the same on every path (Texture::sample and the renderer's
// lanes, so every SIMD level gives the same bits): each texel channel is read as linear light in
// 15 bits (texelFixedTable: kTexelOne is 1.0); across a row the two texels are blended in integers
// with 14-bit weights (the right texel's is truncate(t * kWeightOne), the left's what is left of
// kWeightOne), down the two rows' blends in float, and the result is scaled by kScale. Within a
// 15-bit step of the float filter it replaced; it lets the renderer blend a row's texels in one
// multiply-add of 16-bit pairs and read half the bytes (docs/perf-notes/textured-shading.md).
struct FixedFilter {
  static constexpr int32_t kTexelOne = 32767;
  static constexpr int32_t kWeightOne = 16384;
  static constexpr float kScale = 1.0f / (32767.0f * 16384.0f);
};
// A channel's code (0..255) as the filter reads it, 256 entries: decoded from sRGB (`srgb`, the
// colour channels of an sRGB texture) or code / 255 (the rest, and alpha), times kTexelOne,
// rounded.
const int32_t* texelFixedTable(bool srgb);

// Texture::linearTexels' copy: made once, by the first caller, and not copied with the texture
// (a copy makes its own on first use); a moved texture takes it along with its texels. Its bytes
// count against the process's budget (Texture::kLinearTexelBudget) until it is dropped.
class LinearTexelCache {
 public:
  using LinearLevel = std::vector<int16_t, HugePageAllocator<int16_t>>;
  LinearTexelCache() = default;
  LinearTexelCache(const LinearTexelCache&) {}
  LinearTexelCache(LinearTexelCache&& other) noexcept { *this = std::move(other); }
  LinearTexelCache& operator=(const LinearTexelCache&);
  LinearTexelCache& operator=(LinearTexelCache&& other) noexcept;
  ~LinearTexelCache();

 private:
  friend struct Texture;
  void drop();  // the copy's memory and its share of the budget (under mutex_, or at the end)
  mutable std::mutex mutex_;
  mutable std::atomic<int> state_{0};  // 0: not made yet; 1: made; 2: not made
  // Level 0, then the mips (their bytes: its share of the budget). In huge pages where large: the
  // shading reads a minified texture's copy all over, and its 4 KiB pages' translations cost the
  // textured sphere at 640x480 1.5% of its frame (docs/perf-notes/textured-shading.md).
  mutable std::vector<LinearLevel> levels_;
};

struct Texture {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> texels;  // RGBA8, R in the low byte, row 0 at the top (v = 1 is row 0)
  bool srgb = true;              // texels are sRGB-encoded colour (decode to linear on sampling)
  int source_channels = 0;  // the image file's channels (1 grey ... 4 RGBA); 0: not from a file
  std::vector<TextureLevel> mips;  // levels 1, 2, ... down to 1x1 (generateMipmaps); may be empty

  // Linear RGBA at texture coordinate `uv` (OpenGL convention: v = 0 is the bottom row), from
  // level 0 (kTrilinear samples level 0 bilinearly). `uv` is where the texture is read: the
  // sampler's transform is the caller's (the shading's render::sampleTexture applies it).
  float4 sample(float2 uv, const Sampler& sampler) const;
  // The same at level of detail `lod` (0 = full size, 1 = half size, ...): kTrilinear blends the
  // two levels around it; the other filters use the nearest level.
  float4 sampleLod(float2 uv, float lod, const Sampler& sampler) const;
  int levelCount() const { return 1 + static_cast<int>(mips.size()); }

  // Level `level`'s texels as the bilinear filter reads them (FixedFilter: texelFixedTable's
  // values), four 16-bit channels a texel, in the order of `texels`. The renderer's eight-lane
  // filter loads a texel and its right neighbour at once from it, where the RGBA8 texels take a
  // gather and then a table gather per channel. Made on the first call, for every level at once
  // (other callers wait); null above kLinearTexelLimit texels at level 0 (the copy is twice the
  // texels' memory). The texels must not change once it is made: materials hold their textures
  // const.
  const int16_t* linearTexels(int level) const {
    if (linear_cache.state_.load(std::memory_order_acquire) == 0) makeLinearTexels();
    if (linear_cache.state_.load(std::memory_order_relaxed) != 1 || level < 0 ||
        static_cast<size_t>(level) >= linear_cache.levels_.size())
      return nullptr;
    return linear_cache.levels_[static_cast<size_t>(level)].data();
  }
  static constexpr size_t kLinearTexelLimit = size_t{1} << 20;  // 1024 x 1024: 11 MB with mips
  // The most memory the copies of every texture alive in the process take together: a texture
  // whose copy would pass it samples its RGBA8 texels instead (the same values, more slowly), so
  // that a model with many large maps does not hold twice their memory again.
  static constexpr size_t kLinearTexelBudget = size_t{256} << 20;
  // The copies' bytes now held of the budget; and, for tests, the budget itself (returns the
  // previous one; copies already made keep their memory).
  static size_t linearTexelBytes();
  static size_t setLinearTexelBudget(size_t bytes);
  LinearTexelCache linear_cache;

 private:
  void makeLinearTexels() const;
};

// Texel i of an axis of `size` texels wrapped into [0, size) (any int i, size > 0).
int wrapTexel(int i, int size, TextureWrap wrap);

// Fills texture.mips with a box-filtered chain (averaged in linear light for sRGB textures) down
// to 1x1. Odd sizes round down; each level's texel averages the 2x2 (or fewer) texels above it.
void generateMipmaps(Texture& texture);

}  // namespace tessera
