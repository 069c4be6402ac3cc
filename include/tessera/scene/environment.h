// Environment light (issue 19): an equirectangular image of linear radiance around the scene,
// prepared once into what image-based lighting reads per pixel: the diffuse irradiance as nine
// spherical-harmonic coefficients and the specular radiance prefiltered for a range of
// roughnesses (the split-sum approximation, whose second factor is splitSumBrdf).
//
// Directions are world directions with +Y up. The image's row 0 is straight up (+Y), its last
// row straight down; its columns run once around the vertical axis, column 0 and the image's
// middle column facing -Z and +Z, a quarter in facing +X (equirectUv). An .hdr made for +Y-up
// viewers (the Khronos sample viewer, Blender's world) shows the same way.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera {

// Linear RGB radiance, row 0 at the top (straight up).
struct EnvironmentImage {
  int width = 0;
  int height = 0;
  std::vector<float3> texels;
  const float3& at(int x, int y) const {
    return texels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
  }
};

// equirectUv's arctangent, so that the eight-lane shading code (src/render/environment_lanes.h)
// takes the same float operations as the scalar one, where libm's atan2 and acos would not: atan(a)
// for a in [0, 1] is a times this degree-7 polynomial in a^2 (a least-squares fit on Chebyshev
// nodes; within 1.2e-7 rad of atan, about a float's step at pi / 2).
inline constexpr float kAtanSeries[8] = {
    0.9999992251396179f,  -0.33329537510871887f, 0.19943080842494965f,  -0.13892041146755219f,
    0.09601656347513199f, -0.05538169667124748f, 0.021509254351258278f, -0.003960257396101952f};
// atan2(y, x) through kAtanSeries, in [-pi, pi]; 0 for (0, 0).
float atan2Series(float y, float x);

// The image coordinates (u, v in [0, 1], v = 0 at the top row) that unit direction `d` looks at,
// and the direction at (u, v).
float2 equirectUv(float3 d);
float3 equirectDirection(float2 uv);

// Radiance of `image` in direction `d` (unit), bilinear, wrapping around horizontally; zero for a
// direction that is not finite.
float3 sampleEquirect(const EnvironmentImage& image, float3 d);

class Environment {
 public:
  // Levels of the specular chain: level i holds roughness i / (kSpecularLevels - 1).
  static constexpr int kSpecularLevels = 6;

  Environment() = default;
  // Prepares `image` (finite, non-negative radiance; at least 2x1), scaled by `intensity`. Takes
  // about a second for a 2k image on one core; deterministic.
  explicit Environment(EnvironmentImage image, float intensity = 1.0f);

  bool empty() const { return specular_.empty(); }
  // Irradiance at unit normal n over pi: a white Lambert surface's outgoing radiance.
  float3 diffuse(float3 n) const;
  // The radiance reflected about unit direction r from a GGX lobe of `roughness` (perceptual,
  // in [0, 1]): the first factor of the split sum. Roughness 0 is the image itself (mirror).
  float3 specular(float3 r, float roughness) const;
  // The image as the background shows it (scaled by the intensity).
  const EnvironmentImage& image() const { return specular_.front(); }
  const std::array<float3, 9>& irradianceSh() const { return sh_; }
  // Level i of the specular chain (roughness i / (kSpecularLevels - 1)), level 0 the image: for a
  // GPU port of specular().
  const EnvironmentImage& specularLevel(int i) const { return specular_[static_cast<size_t>(i)]; }

 private:
  std::array<float3, 9> sh_{};              // irradiance / pi, bands 0 to 2
  std::vector<EnvironmentImage> specular_;  // kSpecularLevels levels, level 0 the image
};

// The split sum's second factor (Karis 2013) for the glTF BRDF (GGX distribution, height-
// correlated Smith visibility): the specular reflectance of a lobe is F0 * x + y, for n.v in
// [0, 1] and perceptual roughness in [0, 1]; bilinear in a 32 x 32 table computed once.
float2 splitSumBrdf(float n_dot_v, float roughness);
// The table splitSumBrdf interpolates: kSplitSumTableSize rows (roughness 0 to 1), each of
// kSplitSumTableSize columns (n.v 0 to 1), for a GPU port of it.
constexpr int kSplitSumTableSize = 32;
const float2* splitSumTable();

}  // namespace tessera
