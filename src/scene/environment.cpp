#include <tessera/scene/environment.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

namespace tessera {
namespace {

// The nine real spherical harmonics of bands 0 to 2 at unit direction d.
std::array<float, 9> shBasis(float3 d) {
  return {0.282095f,
          0.488603f * d.y,
          0.488603f * d.z,
          0.488603f * d.x,
          1.092548f * d.x * d.y,
          1.092548f * d.y * d.z,
          0.315392f * (3.0f * d.z * d.z - 1.0f),
          1.092548f * d.x * d.z,
          0.546274f * (d.x * d.x - d.y * d.y)};
}

// Irradiance over pi, as SH coefficients: the radiance's projection, each band scaled by the
// clamped cosine's convolution (Ramamoorthi and Hanrahan 2001: pi, 2 pi / 3, pi / 4) over pi.
std::array<float3, 9> projectIrradiance(const EnvironmentImage& image) {
  std::array<double, 27> sum{};
  const double texel_area =
      (2.0 * std::numbers::pi / image.width) * (std::numbers::pi / image.height);
  for (int y = 0; y < image.height; ++y) {
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(image.height);
    const double solid_angle = texel_area * std::sin(std::numbers::pi * v);
    for (int x = 0; x < image.width; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(image.width);
      const std::array<float, 9> basis = shBasis(equirectDirection({u, v}));
      const float3 radiance = image.at(x, y);
      for (int k = 0; k < 9; ++k) {
        const double w = basis[k] * solid_angle;
        sum[3 * k] += radiance.x * w;
        sum[3 * k + 1] += radiance.y * w;
        sum[3 * k + 2] += radiance.z * w;
      }
    }
  }
  constexpr double kBand[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};
  std::array<float3, 9> sh;
  for (int k = 0; k < 9; ++k)
    sh[k] = {static_cast<float>(sum[3 * k] * kBand[k]),
             static_cast<float>(sum[3 * k + 1] * kBand[k]),
             static_cast<float>(sum[3 * k + 2] * kBand[k])};
  return sh;
}

// Half the size in each direction (at least 1 x 1), each texel the mean of the 2 x 2 above it.
EnvironmentImage halve(const EnvironmentImage& image) {
  EnvironmentImage half;
  half.width = std::max(1, image.width / 2);
  half.height = std::max(1, image.height / 2);
  half.texels.resize(static_cast<size_t>(half.width) * static_cast<size_t>(half.height));
  for (int y = 0; y < half.height; ++y)
    for (int x = 0; x < half.width; ++x) {
      const int x0 = std::min(2 * x, image.width - 1), x1 = std::min(2 * x + 1, image.width - 1);
      const int y0 = std::min(2 * y, image.height - 1), y1 = std::min(2 * y + 1, image.height - 1);
      half.texels[static_cast<size_t>(y) * half.width + x] =
          (image.at(x0, y0) + image.at(x1, y0) + image.at(x0, y1) + image.at(x1, y1)) * 0.25f;
    }
  return half;
}

// Bilinear at level `lod` of `pyramid` (fractional: the two levels around it, blended).
float3 samplePyramid(const std::vector<EnvironmentImage>& pyramid, float3 d, float lod) {
  const float top = static_cast<float>(pyramid.size() - 1);
  lod = std::clamp(lod, 0.0f, top);
  const int lower = static_cast<int>(lod);
  const float t = lod - static_cast<float>(lower);
  const float3 a = sampleEquirect(pyramid[static_cast<size_t>(lower)], d);
  if (t == 0.0f || lower + 1 >= static_cast<int>(pyramid.size())) return a;
  return a * (1.0f - t) + sampleEquirect(pyramid[static_cast<size_t>(lower) + 1], d) * t;
}

// The i-th of n points of the Hammersley set.
float2 hammersley(uint32_t i, uint32_t n) {
  uint32_t bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {static_cast<float>(i) / static_cast<float>(n), static_cast<float>(bits) * 0x1p-32f};
}

// A GGX half vector about +Z for sample point xi; alpha = roughness^2.
float3 ggxHalfVector(float2 xi, float alpha) {
  const float a2 = alpha * alpha;
  const float cos_theta = std::sqrt((1.0f - xi.y) / (1.0f + (a2 - 1.0f) * xi.y));
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * xi.x;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

// Two unit vectors that make an orthonormal frame with unit n.
void frameAround(float3 n, float3& t, float3& b) {
  const float3 up = std::abs(n.y) < 0.999f ? float3{0, 1, 0} : float3{1, 0, 0};
  t = normalize(cross(up, n));
  b = cross(n, t);
}

float ggxD(float n_dot_h, float alpha) {
  const float a2 = alpha * alpha;
  const float f = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * f * f);
}

constexpr uint32_t kPrefilterSamples = 128;

// The GGX-prefiltered radiance about direction n (= the view and reflection directions: the
// split sum's assumption), with filtered importance sampling (Krivanek and Colbert 2008): each
// sample reads the pyramid at the level whose texels cover its share of the lobe.
float3 prefilter(const std::vector<EnvironmentImage>& pyramid, float3 n, float roughness) {
  const float alpha = roughness * roughness;
  float3 t, b;
  frameAround(n, t, b);
  const float texel_solid_angle =
      4.0f * kPi / static_cast<float>(pyramid[0].width * pyramid[0].height);
  float3 sum{0, 0, 0};
  float weight = 0.0f;
  for (uint32_t i = 0; i < kPrefilterSamples; ++i) {
    const float3 hl = ggxHalfVector(hammersley(i, kPrefilterSamples), alpha);
    const float3 h = t * hl.x + b * hl.y + n * hl.z;
    const float n_dot_h = hl.z;  // = v.h, with v = n
    const float3 l = h * (2.0f * n_dot_h) - n;
    const float n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0f) continue;
    const float pdf = ggxD(n_dot_h, alpha) * 0.25f;
    const float sample_solid_angle = 1.0f / (static_cast<float>(kPrefilterSamples) * pdf + 1e-6f);
    const float lod = 0.5f * std::log2(sample_solid_angle / texel_solid_angle) + 1.0f;
    sum += samplePyramid(pyramid, l, lod) * n_dot_l;
    weight += n_dot_l;
  }
  return weight > 0.0f ? sum * (1.0f / weight) : float3{0, 0, 0};
}

// Level `level` (>= 1) of the specular chain, its rows shared among threads (each texel is
// computed alone, so the result does not depend on how many).
EnvironmentImage prefilterLevel(const std::vector<EnvironmentImage>& pyramid, int level) {
  EnvironmentImage out;
  out.width = std::max(16, std::min(256, pyramid[0].width) >> (level - 1));
  out.height = std::max(8, out.width / 2);
  out.texels.resize(static_cast<size_t>(out.width) * static_cast<size_t>(out.height));
  const float roughness = static_cast<float>(level) / (Environment::kSpecularLevels - 1);
  auto rows = [&](int first, int step) {
    for (int y = first; y < out.height; y += step)
      for (int x = 0; x < out.width; ++x) {
        const float2 uv{(static_cast<float>(x) + 0.5f) / static_cast<float>(out.width),
                        (static_cast<float>(y) + 0.5f) / static_cast<float>(out.height)};
        out.texels[static_cast<size_t>(y) * out.width + x] =
            prefilter(pyramid, equirectDirection(uv), roughness);
      }
  };
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(rows, i, threads);
  rows(0, threads);
  for (std::thread& thread : pool) thread.join();
  return out;
}

}  // namespace

float atan2Series(float y, float x) {
  const float ax = std::fabs(x), ay = std::fabs(y);
  const bool steep = ax < ay;
  const float big = steep ? ay : ax, small = steep ? ax : ay;
  const float a = big > 0.0f ? small / big : 0.0f;
  const float s = a * a;
  float p = kAtanSeries[7];
  for (int i = 6; i >= 0; --i) p = p * s + kAtanSeries[i];
  float r = p * a;
  if (steep) r = 0.5f * kPi - r;
  if (x < 0.0f) r = kPi - r;
  if (y < 0.0f) r = -r;
  return r;
}

float2 equirectUv(float3 d) {
  float u = atan2Series(d.x, -d.z) / (2.0f * kPi);
  if (u < 0.0f) u += 1.0f;
  // acos(y) = atan2(sin, cos), the sine from (1 - y)(1 + y), exact near y = +-1.
  const float y = std::clamp(d.y, -1.0f, 1.0f);
  const float v = atan2Series(std::sqrt((1.0f - y) * (1.0f + y)), y) / kPi;
  return {u, v};
}

float3 equirectDirection(float2 uv) {
  const float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
  const float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

float3 sampleEquirect(const EnvironmentImage& image, float3 d) {
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) return {0, 0, 0};
  const float2 uv = equirectUv(d);
  const float fx = uv.x * static_cast<float>(image.width) - 0.5f;
  const float fy = std::clamp(uv.y * static_cast<float>(image.height) - 0.5f, 0.0f,
                              static_cast<float>(image.height - 1));
  const float x_floor = std::floor(fx), y_floor = std::floor(fy);
  const float tx = fx - x_floor, ty = fy - y_floor;
  const int x0 = ((static_cast<int>(x_floor) % image.width) + image.width) % image.width;
  const int x1 = (x0 + 1) % image.width;
  const int y0 = static_cast<int>(y_floor), y1 = std::min(y0 + 1, image.height - 1);
  const float3 top = image.at(x0, y0) * (1.0f - tx) + image.at(x1, y0) * tx;
  const float3 bottom = image.at(x0, y1) * (1.0f - tx) + image.at(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

Environment::Environment(EnvironmentImage image, float intensity) {
  for (float3& texel : image.texels) texel = texel * intensity;
  sh_ = projectIrradiance(image);
  std::vector<EnvironmentImage> pyramid{image};
  while (pyramid.back().height > 1 && pyramid.back().width > 2)
    pyramid.push_back(halve(pyramid.back()));
  specular_.reserve(kSpecularLevels);
  specular_.push_back(std::move(image));
  for (int level = 1; level < kSpecularLevels; ++level)
    specular_.push_back(prefilterLevel(pyramid, level));
}

float3 Environment::diffuse(float3 n) const {
  const std::array<float, 9> basis = shBasis(n);
  float3 sum{0, 0, 0};
  for (int k = 0; k < 9; ++k) sum += sh_[k] * basis[k];
  return {std::max(sum.x, 0.0f), std::max(sum.y, 0.0f), std::max(sum.z, 0.0f)};
}

float3 Environment::specular(float3 r, float roughness) const {
  // fmax and fmin take a NaN to the bound: a lane nobody stores may hold one.
  const float lod = std::fmin(std::fmax(roughness, 0.0f), 1.0f) * (kSpecularLevels - 1);
  const int lower = std::min(static_cast<int>(lod), kSpecularLevels - 2);
  const float t = lod - static_cast<float>(lower);
  return sampleEquirect(specular_[lower], r) * (1.0f - t) +
         sampleEquirect(specular_[lower + 1], r) * t;
}

namespace {

constexpr int kLutSize = kSplitSumTableSize;
constexpr uint32_t kLutSamples = 512;

// One entry of the split-sum table: the integral over GGX half vectors of the glTF specular
// BRDF times n.l, split into the parts F0 scales and the part it does not.
float2 integrateBrdf(float n_dot_v, float roughness) {
  const float alpha = roughness * roughness, a2 = alpha * alpha;
  const float3 v{std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v};
  float scale = 0.0f, bias = 0.0f;
  for (uint32_t i = 0; i < kLutSamples; ++i) {
    const float3 h = ggxHalfVector(hammersley(i, kLutSamples), alpha);
    const float v_dot_h = dot(v, h);
    const float3 l = h * (2.0f * v_dot_h) - v;
    const float n_dot_l = l.z, n_dot_h = h.z;
    if (n_dot_l <= 0.0f || v_dot_h <= 0.0f) continue;
    // Height-correlated Smith visibility V = G / (4 n.l n.v), as glTF's appendix B.
    const float vis = 0.5f / (n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2) +
                              n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2));
    // f n.l / pdf, with pdf = D n.h / (4 v.h): D cancels.
    const float g = 4.0f * vis * n_dot_l * v_dot_h / n_dot_h;
    const float fc = std::pow(1.0f - v_dot_h, 5.0f);
    scale += (1.0f - fc) * g;
    bias += fc * g;
  }
  return {scale / kLutSamples, bias / kLutSamples};
}

struct BrdfLut {
  std::array<float2, kLutSize * kLutSize> entries;  // [roughness row][n.v column]
  BrdfLut() {
    for (int r = 0; r < kLutSize; ++r)
      for (int c = 0; c < kLutSize; ++c) {
        const float n_dot_v = std::max(static_cast<float>(c) / (kLutSize - 1), 1.0f / 256.0f);
        entries[static_cast<size_t>(r * kLutSize + c)] =
            integrateBrdf(n_dot_v, static_cast<float>(r) / (kLutSize - 1));
      }
  }
};

const BrdfLut& brdfLut() {
  static const BrdfLut lut;
  return lut;
}

}  // namespace

const float2* splitSumTable() {
  return brdfLut().entries.data();
}

float2 splitSumBrdf(float n_dot_v, float roughness) {
  const BrdfLut& lut = brdfLut();
  // fmax and fmin take a NaN to the bound: a lane nobody stores may hold one.
  const float fx = std::fmin(std::fmax(n_dot_v, 0.0f), 1.0f) * (kLutSize - 1);
  const float fy = std::fmin(std::fmax(roughness, 0.0f), 1.0f) * (kLutSize - 1);
  const int x0 = std::min(static_cast<int>(fx), kLutSize - 2);
  const int y0 = std::min(static_cast<int>(fy), kLutSize - 2);
  const float tx = fx - static_cast<float>(x0), ty = fy - static_cast<float>(y0);
  auto at = [&](int x, int y) { return lut.entries[static_cast<size_t>(y * kLutSize + x)]; };
  const float2 top = at(x0, y0) * (1.0f - tx) + at(x0 + 1, y0) * tx;
  const float2 bottom = at(x0, y0 + 1) * (1.0f - tx) + at(x0 + 1, y0 + 1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

}  // namespace tessera
