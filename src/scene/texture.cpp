#include <tessera/scene/texture.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <new>
#include <utility>

#include <tessera/scene/color.h>

namespace tessera {

namespace {

struct LevelView {
  int width, height;
  const uint32_t* texels;
};

// Texels i and i + 1 along an axis, wrapped; the common case (both inside) takes no division.
void wrapPair(int i, int size, TextureWrap wrap, int& first, int& second) {
  if (i >= 0 && i + 1 < size) {
    first = i;
    second = i + 1;
    return;
  }
  first = wrapTexel(i, size, wrap);
  second = wrapTexel(i + 1, size, wrap);
}

inline __attribute__((always_inline)) float4 decodeTexel(uint32_t c, bool srgb,
                                                         const float* decode) {
  float a = static_cast<float>(c >> 24) / 255.0f;
  if (srgb) return {decode[c & 0xff], decode[(c >> 8) & 0xff], decode[(c >> 16) & 0xff], a};
  return {static_cast<float>(c & 0xff) / 255.0f, static_cast<float>((c >> 8) & 0xff) / 255.0f,
          static_cast<float>((c >> 16) & 0xff) / 255.0f, a};
}

// A texel's four channels as the bilinear filter reads them (texelFixedTable).
inline __attribute__((always_inline)) void fixedTexel(uint32_t c, const int32_t* colour,
                                                      const int32_t* unorm, int32_t out[4]) {
  out[0] = colour[c & 0xff];
  out[1] = colour[(c >> 8) & 0xff];
  out[2] = colour[(c >> 16) & 0xff];
  out[3] = unorm[c >> 24];
}

// Keeps float-to-int conversions defined for huge or non-finite coordinates (fmod only where
// it changes something: below 65536 it is the identity).
float sanitize(float v) {
  if (std::fabs(v) < 65536.0f) return v;
  return std::isfinite(v) ? std::fmod(v, 65536.0f) : 0.0f;
}

float4 sampleLevel(const LevelView& level, bool srgb, float2 uv, TextureFilter filter,
                   TextureWrap wrap_s, TextureWrap wrap_t) {
  const float* decode = srgbDecodeTable();
  // Texel space: x right, y down from the top row (v = 1 is the top edge).
  const float fx = sanitize(uv.x) * level.width;
  const float fy = (1.0f - sanitize(uv.y)) * level.height;
  auto texel = [&](int x, int y) {
    return decodeTexel(level.texels[static_cast<size_t>(y) * level.width + x], srgb, decode);
  };
  if (filter == TextureFilter::kNearest) {
    return texel(wrapTexel(static_cast<int>(std::floor(fx)), level.width, wrap_s),
                 wrapTexel(static_cast<int>(std::floor(fy)), level.height, wrap_t));
  }
  // Bilinear between the four nearest texel centres, in linear space, in fixed point across
  // (FixedFilter).
  const float sx = fx - 0.5f, sy = fy - 0.5f;
  const float x0f = std::floor(sx), y0f = std::floor(sy);
  const float tx = sx - x0f, ty = sy - y0f;
  const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
  int xa, xb, ya, yb;
  wrapPair(x0, level.width, wrap_s, xa, xb);
  wrapPair(y0, level.height, wrap_t, ya, yb);
  const int32_t* colour = texelFixedTable(srgb);
  const int32_t* unorm = texelFixedTable(false);
  int32_t q[4][4];  // the quad's texels: (xa, ya), (xb, ya), (xa, yb), (xb, yb)
  const int xs[2] = {xa, xb}, ys[2] = {ya, yb};
  for (int i = 0; i < 4; ++i)
    fixedTexel(level.texels[static_cast<size_t>(ys[i / 2]) * level.width + xs[i % 2]], colour,
               unorm, q[i]);
  const int32_t w1 = static_cast<int32_t>(tx * static_cast<float>(FixedFilter::kWeightOne));
  const int32_t w0 = FixedFilter::kWeightOne - w1;
  float out[4];
  for (int k = 0; k < 4; ++k) {
    const float upper = static_cast<float>(q[0][k] * w0 + q[1][k] * w1);
    const float lower = static_cast<float>(q[2][k] * w0 + q[3][k] * w1);
    out[k] = (upper + (lower - upper) * ty) * FixedFilter::kScale;
  }
  return {out[0], out[1], out[2], out[3]};
}

LevelView levelView(const Texture& t, int level) {
  if (level <= 0) return {t.width, t.height, t.texels.data()};
  const TextureLevel& m = t.mips[static_cast<size_t>(level - 1)];
  return {m.width, m.height, m.texels.data()};
}

// Whether every level's texel vector holds its width x height texels (what reading them takes).
bool levelsHoldTheirTexels(const Texture& t) {
  if (t.texels.size() != static_cast<size_t>(t.width) * static_cast<size_t>(std::max(t.height, 0)))
    return false;
  for (const TextureLevel& m : t.mips)
    if (m.width < 0 || m.texels.size() != static_cast<size_t>(m.width) *
                                              static_cast<size_t>(std::max(m.height, 0)))
      return false;
  return t.width >= 0;
}

// Every level of t as the bilinear filter reads it (Texture::linearTexels).
void decodeLevels(const Texture& t, std::vector<LinearTexelCache::LinearLevel>& levels) {
  const int32_t* colour = texelFixedTable(t.srgb);
  const int32_t* unorm = texelFixedTable(false);
  levels.resize(static_cast<size_t>(t.levelCount()));
  for (int l = 0; l < t.levelCount(); ++l) {
    const LevelView view = levelView(t, l);
    const size_t count = static_cast<size_t>(view.width) * static_cast<size_t>(view.height);
    LinearTexelCache::LinearLevel& out = levels[static_cast<size_t>(l)];
    out.resize(4 * count);
    for (size_t i = 0; i < count; ++i) {
      int32_t c[4];
      fixedTexel(view.texels[i], colour, unorm, c);
      for (int k = 0; k < 4; ++k) out[4 * i + k] = static_cast<int16_t>(c[k]);
    }
  }
}

}  // namespace

int wrapTexel(int i, int size, TextureWrap wrap) {
  if (wrap == TextureWrap::kClamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
  if (wrap == TextureWrap::kRepeat) {
    const int m = i % size;
    return m < 0 ? m + size : m;
  }
  // Mirrored: (size - 1) - mirror((i mod 2 size) - size), which is m below size and
  // 2 size - 1 - m from there.
  const int period = 2 * size;
  int m = i % period;
  if (m < 0) m += period;
  return m < size ? m : period - 1 - m;
}

bool TextureTransform::finite() const {
  return std::isfinite(offset.x) && std::isfinite(offset.y) && std::isfinite(rotation) &&
         std::isfinite(scale.x) && std::isfinite(scale.y);
}

UvAffine TextureTransform::affine() const {
  // The extension's T(offset) R(rotation) S(scale) with the rotation's rows (c, s) and (-s, c),
  // its README's mat3 read row by row: rows (c sx, s sy, ox) and (-s sx, c sy, oy). (Read as
  // GLSL's column-major mat3 it would turn the other way, which Khronos' TextureTransformTest
  // marks red.) Then taken to v' = 1 - v on both sides.
  const double c = rotation == 0.0f ? 1.0 : std::cos(static_cast<double>(rotation));
  const double s = rotation == 0.0f ? 0.0 : std::sin(static_cast<double>(rotation));
  const double sx = scale.x, sy = scale.y, ox = offset.x, oy = offset.y;
  UvAffine m;
  m.m00 = static_cast<float>(c * sx);
  m.m01 = static_cast<float>(-s * sy);
  m.m02 = static_cast<float>(s * sy + ox);
  m.m10 = static_cast<float>(s * sx);
  m.m11 = static_cast<float>(c * sy);
  m.m12 = static_cast<float>(1.0 - c * sy - oy);
  return m;
}

const int32_t* texelFixedTable(bool srgb) {
  static const auto tables = [] {
    std::array<std::array<int32_t, 256>, 2> t{};
    const float* decode = srgbDecodeTable();
    for (int c = 0; c < 256; ++c) {
      t[0][static_cast<size_t>(c)] = static_cast<int32_t>(
          std::lround(static_cast<double>(c) * FixedFilter::kTexelOne / 255.0));
      t[1][static_cast<size_t>(c)] = static_cast<int32_t>(
          std::lround(static_cast<double>(decode[c]) * FixedFilter::kTexelOne));
    }
    return t;
  }();
  return tables[srgb ? 1 : 0].data();
}

float4 Texture::sample(float2 uv, const Sampler& sampler) const {
  if (width <= 0 || height <= 0) return {1, 1, 1, 1};
  const TextureFilter filter = sampler.filter == TextureFilter::kNearest ? TextureFilter::kNearest
                                                                         : TextureFilter::kBilinear;
  return sampleLevel(levelView(*this, 0), srgb, uv, filter, sampler.wrap_s, sampler.wrap_t);
}

float4 Texture::sampleLod(float2 uv, float lod, const Sampler& sampler) const {
  if (width <= 0 || height <= 0) return {1, 1, 1, 1};
  const int last = levelCount() - 1;
  if (!(lod > 0.0f)) lod = 0.0f;  // also catches NaN
  if (lod > static_cast<float>(last)) lod = static_cast<float>(last);
  if (sampler.filter != TextureFilter::kTrilinear) {
    const int level = static_cast<int>(lod + 0.5f);
    return sampleLevel(levelView(*this, level), srgb, uv, sampler.filter, sampler.wrap_s,
                       sampler.wrap_t);
  }
  const int lower = static_cast<int>(lod);
  const float blend = lod - static_cast<float>(lower);
  const float4 a = sampleLevel(levelView(*this, lower), srgb, uv, TextureFilter::kBilinear,
                               sampler.wrap_s, sampler.wrap_t);
  if (blend == 0.0f || lower >= last) return a;
  const float4 b = sampleLevel(levelView(*this, lower + 1), srgb, uv, TextureFilter::kBilinear,
                               sampler.wrap_s, sampler.wrap_t);
  return lerp(a, b, blend);
}

namespace {

std::atomic<size_t> linear_texel_bytes{0};
std::atomic<size_t> linear_texel_budget{Texture::kLinearTexelBudget};

// Takes `bytes` of the copies' budget; false, with nothing taken, where they would pass it.
bool reserveLinearTexels(size_t bytes) {
  const size_t budget = linear_texel_budget.load(std::memory_order_relaxed);
  size_t held = linear_texel_bytes.load(std::memory_order_relaxed);
  do {
    if (bytes > budget || held > budget - bytes) return false;
  } while (!linear_texel_bytes.compare_exchange_weak(held, held + bytes));
  return true;
}

// The bytes of the linear copy of every level of t: four 16-bit channels a texel.
size_t linearBytes(const Texture& t) {
  size_t texels = 0;
  for (int l = 0; l < t.levelCount(); ++l) {
    const LevelView view = levelView(t, l);
    texels += static_cast<size_t>(view.width) * static_cast<size_t>(view.height);
  }
  return 4 * sizeof(int16_t) * texels;
}

}  // namespace

size_t Texture::linearTexelBytes() {
  return linear_texel_bytes.load();
}

size_t Texture::setLinearTexelBudget(size_t bytes) {
  return linear_texel_budget.exchange(bytes);
}

void LinearTexelCache::drop() {
  size_t channels = 0;  // what makeLinearTexels reserved: linearBytes of the texture it was made of
  for (const LinearLevel& level : levels_) channels += level.size();
  linear_texel_bytes.fetch_sub(sizeof(int16_t) * channels);
  levels_.clear();
  levels_.shrink_to_fit();
}

LinearTexelCache::~LinearTexelCache() {
  drop();
}

LinearTexelCache& LinearTexelCache::operator=(const LinearTexelCache&) {
  // The texture it belongs to takes new texels: the next linearTexels makes the copy again.
  std::lock_guard lock(mutex_);
  drop();
  state_.store(0, std::memory_order_release);
  return *this;
}

LinearTexelCache& LinearTexelCache::operator=(LinearTexelCache&& other) noexcept {
  // The texels move with it: the copy still holds their values.
  if (this == &other) return *this;
  std::scoped_lock lock(mutex_, other.mutex_);
  drop();
  levels_ = std::move(other.levels_);
  other.levels_.clear();  // its share of the budget moves with the levels
  state_.store(other.state_.exchange(0), std::memory_order_release);
  return *this;
}

void Texture::makeLinearTexels() const {
  const LinearTexelCache& cache = linear_cache;  // its members are mutable
  std::lock_guard lock(cache.mutex_);
  if (cache.state_.load(std::memory_order_relaxed) != 0) return;  // another thread made it
  int state = 2;
  if (static_cast<size_t>(width) * static_cast<size_t>(height) <= kLinearTexelLimit &&
      levelsHoldTheirTexels(*this)) {
    const size_t bytes = linearBytes(*this);
    if (reserveLinearTexels(bytes)) {
      try {
        decodeLevels(*this, cache.levels_);  // 2 bytes a channel: bytes in all
        state = 1;
      } catch (const std::bad_alloc&) {
        cache.levels_.clear();  // without the copy, sampling reads the RGBA8 texels
        linear_texel_bytes.fetch_sub(bytes);
      }
    }
  }
  cache.state_.store(state, std::memory_order_release);
}

void generateMipmaps(Texture& texture) {
  texture.linear_cache = LinearTexelCache();  // made again, with the new levels, on next use
  texture.mips.clear();
  LevelView above{texture.width, texture.height, texture.texels.data()};
  while (above.width > 1 || above.height > 1) {
    TextureLevel level;
    level.width = std::max(1, above.width / 2);
    level.height = std::max(1, above.height / 2);
    level.texels.resize(static_cast<size_t>(level.width) * level.height);
    for (int y = 0; y < level.height; ++y) {
      for (int x = 0; x < level.width; ++x) {
        float4 sum{};
        int count = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = 2 * x + dx, sy = 2 * y + dy;
            if (sx >= above.width || sy >= above.height) continue;
            sum = sum + decodeTexel(above.texels[static_cast<size_t>(sy) * above.width + sx],
                                    texture.srgb, srgbDecodeTable());
            ++count;
          }
        const float4 mean = sum * (1.0f / static_cast<float>(count));
        auto unorm = [](float v) {
          return static_cast<uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        };
        const uint32_t rgb = texture.srgb
                                 ? (static_cast<uint32_t>(encodeSrgb8(mean.x)) |
                                    (static_cast<uint32_t>(encodeSrgb8(mean.y)) << 8) |
                                    (static_cast<uint32_t>(encodeSrgb8(mean.z)) << 16))
                                 : (unorm(mean.x) | (unorm(mean.y) << 8) | (unorm(mean.z) << 16));
        level.texels[static_cast<size_t>(y) * level.width + x] = rgb | (unorm(mean.w) << 24);
      }
    }
    texture.mips.push_back(std::move(level));
    const TextureLevel& made = texture.mips.back();
    above = {made.width, made.height, made.texels.data()};
  }
}

}  // namespace tessera
