// OBJ polygons to triangles (obj_loader.cpp): the fan or ear clipping the triangle-id contract
// fixes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <tessera/math/vec.h>

namespace tessera::io {

// Reflex-vertex tests the ear clipper may make for one file: a few seconds of work. Real models
// use a tiny fraction; a file of huge concave polygons built to be slow is refused instead.
constexpr uint64_t kEarClipBudget = 1'000'000'000;

// Splits polygons into triangles of corner numbers in the order the triangle-id contract fixes:
// a convex polygon is a fan from its first corner, a concave one is ear-clipped. Both decisions
// are made in the polygon's best-fit plane (Newell's normal), so a slightly warped polygon is
// treated as it looks. The ear clipper is Eberly's ("Triangulation by Ear Clipping"): only
// reflex corners can lie inside an ear, and clipping an ear changes only its two neighbours.
class PolygonSplitter {
 public:
  // Which edges of the triangle of corners[0..2] of an n-gon are polygon sides (corners next
  // to each other, first and last included): Mesh::triangle_edges' bits.
  static uint8_t outlineEdges(const uint32_t corners[3], size_t n) {
    if (n == 3) return 0b111;  // most files: no division
    auto side = [&](int k) {
      const size_t p = corners[k], q = corners[(k + 1) % 3];
      return (p + 1) % n == q || (q + 1) % n == p;
    };
    return static_cast<uint8_t>(side(0) | side(1) << 1 | side(2) << 2);
  }

  // Appends n - 2 triangles (corner numbers, the polygon's winding) to `triangles`. False when
  // the file's ear-clipping budget has run out.
  bool split(std::span<const float3> corners, std::vector<uint32_t>& triangles) {
    const int n = static_cast<int>(corners.size());
    auto fan = [&] {
      for (int i = 1; i + 1 < n; ++i) append(triangles, 0, i, i + 1);
    };
    if (n <= 3) {
      fan();
      return true;
    }
    // Newell's normal, around the first corner for precision.
    const float3 origin = corners[0];
    double normal[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
      float3 a = corners[i] - origin, b = corners[(i + 1) % n] - origin;
      normal[0] += (double(a.y) - b.y) * (double(a.z) + b.z);
      normal[1] += (double(a.z) - b.z) * (double(a.x) + b.x);
      normal[2] += (double(a.x) - b.x) * (double(a.y) + b.y);
    }
    if (!std::isfinite(normal[0] + normal[1] + normal[2]) ||
        (normal[0] == 0 && normal[1] == 0 && normal[2] == 0)) {
      // No plane (non-finite or degenerate corners): nothing to clip against.
      fan();
      return true;
    }
    // Drop the normal's dominant axis; keep the other two in the order that makes the polygon
    // counter-clockwise (x, y for +z; y, z for +x; z, x for +y).
    int k = 0;
    for (int axis = 1; axis < 3; ++axis)
      if (std::abs(normal[axis]) > std::abs(normal[k])) k = axis;
    int u = (k + 1) % 3, v = (k + 2) % 3;
    if (normal[k] < 0) std::swap(u, v);
    x_.resize(n);
    y_.resize(n);
    for (int i = 0; i < n; ++i) {
      x_[i] = double(corners[i][u]) - origin[u];
      y_[i] = double(corners[i][v]) - origin[v];
    }
    if (isConvex(n)) {
      fan();
      return true;
    }
    return clipEars(n, triangles);
  }

 private:
  static void append(std::vector<uint32_t>& triangles, int a, int b, int c) {
    triangles.push_back(static_cast<uint32_t>(a));
    triangles.push_back(static_cast<uint32_t>(b));
    triangles.push_back(static_cast<uint32_t>(c));
  }

  // Twice the signed area of (a, b, c): positive for a left turn.
  double orient(int a, int b, int c) const {
    return (x_[b] - x_[a]) * (y_[c] - y_[a]) - (y_[b] - y_[a]) * (x_[c] - x_[a]);
  }

  // Every turn to the left (collinear within a hair counts) and one full turn in all: a star
  // polygon turns left everywhere but twice around.
  bool isConvex(int n) const {
    constexpr double kCollinear = 1e-6;  // sine of the largest right turn still called straight
    double turning = 0;
    for (int i = 0; i < n; ++i) {
      int a = (i + n - 1) % n, c = (i + 1) % n;
      double e1x = x_[i] - x_[a], e1y = y_[i] - y_[a];
      double e2x = x_[c] - x_[i], e2y = y_[c] - y_[i];
      double cross = e1x * e2y - e1y * e2x;
      double dot = e1x * e2x + e1y * e2y;
      if (cross < -kCollinear * std::hypot(e1x, e1y) * std::hypot(e2x, e2y)) return false;
      turning += std::atan2(cross, dot);
    }
    return std::abs(turning - 2 * std::numbers::pi) < std::numbers::pi;
  }

  bool isEar(int v) {
    if (!convex_[v]) return false;
    const int a = prev_[v], c = next_[v];
    for (int j : reflex_) {
      if (j == a || j == v || j == c) continue;
      if (++work_ > kEarClipBudget) return false;
      // A corner repeated at the same place (a hole joined by a bridge) does not block.
      auto same = [&](int p) { return x_[j] == x_[p] && y_[j] == y_[p]; };
      if (same(a) || same(v) || same(c)) continue;
      if (orient(a, v, j) >= 0 && orient(v, c, j) >= 0 && orient(c, a, j) >= 0) return false;
    }
    return true;
  }

  bool clipEars(int n, std::vector<uint32_t>& triangles) {
    prev_.resize(n);
    next_.resize(n);
    convex_.resize(n);
    ear_.resize(n);
    for (int i = 0; i < n; ++i) {
      prev_[i] = (i + n - 1) % n;
      next_[i] = (i + 1) % n;
    }
    reflex_.clear();
    for (int i = 0; i < n; ++i) {
      convex_[i] = orient(prev_[i], i, next_[i]) > 0;
      if (!convex_[i]) reflex_.push_back(i);
    }
    for (int i = 0; i < n; ++i) ear_[i] = isEar(i);
    int remaining = n, cursor = 0;
    while (remaining > 3) {
      if (work_ > kEarClipBudget) return false;
      int clip = -1;
      for (int k = 0, v = cursor; k < remaining; ++k, v = next_[v])
        if (ear_[v]) {
          clip = v;
          break;
        }
      if (clip < 0) {
        // Self-intersecting or degenerate: no true ear. Clipping a convex corner (or any) still
        // ends in n - 2 triangles.
        clip = cursor;
        for (int k = 0, v = cursor; k < remaining; ++k, v = next_[v])
          if (convex_[v]) {
            clip = v;
            break;
          }
      }
      const int a = prev_[clip], b = next_[clip];
      append(triangles, a, clip, b);
      next_[a] = b;
      prev_[b] = a;
      --remaining;
      convex_[a] = orient(prev_[a], a, b) > 0;
      convex_[b] = orient(a, b, next_[b]) > 0;
      std::erase_if(reflex_, [&](int j) { return j == clip || convex_[j]; });
      // Only a degenerate polygon turns a convex neighbour reflex.
      for (int v : {a, b})
        if (!convex_[v] && std::find(reflex_.begin(), reflex_.end(), v) == reflex_.end())
          reflex_.push_back(v);
      ear_[a] = isEar(a);
      ear_[b] = isEar(b);
      cursor = b;
    }
    append(triangles, prev_[cursor], cursor, next_[cursor]);
    return work_ <= kEarClipBudget;
  }

  std::vector<double> x_, y_;
  std::vector<int> prev_, next_;
  std::vector<char> convex_, ear_;
  std::vector<int> reflex_;  // reflex corners still in the polygon: the only ones an ear can hold
  uint64_t work_ = 0;
};

}  // namespace tessera::io
