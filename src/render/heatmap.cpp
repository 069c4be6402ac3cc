#include <tessera/render/heatmap.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tessera {

namespace {

uint32_t packRgb(uint32_t r, uint32_t g, uint32_t b) {
  return r | (g << 8) | (b << 16) | 0xff000000u;
}

// 3x5 digits, a row per 3 bits (top row first, high bit left).
constexpr uint16_t kDigits[10] = {075557, 026227, 071747, 071717, 055711,
                                  074717, 074757, 071111, 075757, 075717};

void drawNumber(std::vector<uint32_t>& image, int width, int x, int y, int scale, uint64_t n,
                bool align_right) {
  const std::string text = std::to_string(n);
  const int advance = 4 * scale;
  int left = align_right ? x - static_cast<int>(text.size()) * advance + scale : x;
  for (char ch : text) {
    const uint16_t glyph = kDigits[ch - '0'];
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col) {
        if (!((glyph >> (12 - 3 * row + (2 - col))) & 1)) continue;
        for (int sy = 0; sy < scale; ++sy)
          for (int sx = 0; sx < scale; ++sx) {
            const int px = left + col * scale + sx, py = y + row * scale + sy;
            if (px >= 0 && px < width)
              image[static_cast<size_t>(py) * width + px] = packRgb(255, 255, 255);
          }
      }
    left += advance;
  }
}

}  // namespace

// Inferno (matplotlib), five stops, linear between them.
uint32_t infernoColor(float t) {
  static constexpr float kStops[5][3] = {
      {0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
  const float s = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(static_cast<int>(s), 3);
  const float f = s - static_cast<float>(i);
  uint32_t c[3];
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<uint32_t>(std::lround(kStops[i][k] + (kStops[i + 1][k] - kStops[i][k]) * f));
  return packRgb(c[0], c[1], c[2]);
}

namespace {

// Legend glyphs are drawn `scale` pixels to a font pixel.
int legendScale(int height) {
  return std::clamp(height / 160, 1, 4);
}

}  // namespace

int heatmapLegendHeight(int width, int height) {
  const int scale = legendScale(height);
  const int strip = 9 * scale;
  return height < 2 * strip || width < 40 * scale ? 0 : strip;
}

std::vector<uint32_t> heatmapImage(int width, int height, const std::vector<uint32_t>& counts,
                                   std::optional<uint32_t> top_count) {
  const uint32_t top = top_count        ? *top_count
                       : counts.empty() ? 0
                                        : *std::max_element(counts.begin(), counts.end());
  std::vector<uint32_t> image(counts.size());
  for (size_t i = 0; i < counts.size(); ++i)
    image[i] = infernoColor(top ? static_cast<float>(counts[i]) / static_cast<float>(top) : 0.0f);
  // The legend: a strip along the bottom, the ramp between the labels 0 and the top count.
  const int scale = legendScale(height);
  const int strip = heatmapLegendHeight(width, height);
  if (strip == 0) return image;  // too small to label
  const int y0 = height - strip;
  for (int y = y0; y < height; ++y)
    std::fill_n(&image[static_cast<size_t>(y) * width], width, packRgb(0, 0, 0));
  const int label = 4 * scale * (static_cast<int>(std::to_string(top).size()) + 1);
  const int bar_left = 6 * scale, bar_right = width - label - 2 * scale;
  for (int y = y0 + 2 * scale; y < height - 2 * scale; ++y)
    for (int x = bar_left; x < bar_right; ++x)
      image[static_cast<size_t>(y) * width + x] = infernoColor(
          static_cast<float>(x - bar_left) / static_cast<float>(bar_right - bar_left - 1));
  drawNumber(image, width, scale, y0 + 2 * scale, scale, 0, false);
  drawNumber(image, width, width - scale, y0 + 2 * scale, scale, top, true);
  return image;
}

}  // namespace tessera
