#include <tessera/model/ground_grid.h>

#include <algorithm>
#include <cmath>

namespace tessera::model {

namespace {

// The grid's grey (linear RGB): visible on the default 0.2 grey background and on white, and
// quieter than the axes.
constexpr float3 kGridColor{0.12f, 0.12f, 0.12f};

}  // namespace

float gridUnit(const Bounds& bounds) {
  const float radius = std::max(bounds.radius(), 1e-30f);
  return 0.5f * std::pow(10.0f, std::floor(std::log10(radius)));
}

void appendGroundGrid(const Bounds& bounds, float3 up, LineList& lines) {
  if (bounds.empty()) return;
  // The world axis up runs along, and the two across it.
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(up[k]) > std::fabs(up[axis])) axis = k;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  const float unit = gridUnit(bounds);
  const float half = std::ceil(1.5f * bounds.radius() / unit) * unit;
  float3 centre = bounds.center();
  centre[a] = std::round(centre[a] / unit) * unit;
  centre[b] = std::round(centre[b] / unit) * unit;
  // The lowest point along `up` (which may point down an axis), a thousandth of a cell lower.
  const float low = up[axis] > 0 ? bounds.min[axis] : bounds.max[axis];
  centre[axis] = low - (up[axis] > 0 ? 1.0f : -1.0f) * 1e-3f * unit;
  const int cells = static_cast<int>(std::lround(2.0f * half / unit));
  for (int i = 0; i <= cells; ++i) {
    const float offset = -half + static_cast<float>(i) * unit;
    for (int dir = 0; dir < 2; ++dir) {
      const int along = dir == 0 ? a : b, across = dir == 0 ? b : a;
      float3 from = centre, to = centre;
      from[across] = to[across] = centre[across] + offset;
      from[along] -= half;
      to[along] += half;
      lines.add(from, to, kGridColor);
    }
  }
}

}  // namespace tessera::model
