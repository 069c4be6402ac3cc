// Frustum and cluster culling, before the vertex stage: every object with clusters
// (Object::clusters) is tested by its bounds against the view frustum, then each of its clusters
// by its bounds and, when the object culls a face, by its normal cone. What survives is a list of
// triangle ranges per object (setup reads only those) and of vertex ranges (the vertex stage
// transforms only those). Conservative: a rejected triangle is one the per-triangle tests would
// have dropped (wholly outside one of the planes the outcodes test, or facing away by a margin),
// so the image does not change by a pixel. Objects without clusters are drawn whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/scene/scene.h>

#include "render/vertex.h"

namespace tessera::render {

struct IndexRange {
  size_t first, end;
};

struct CullCounters {
  size_t instances_culled = 0, clusters_culled = 0, clusters_facing = 0;
  size_t triangles_in_culled_instances = 0, triangles_in_culled_clusters = 0;
};

class FrustumCull {
 public:
  // The ranges of every object this frame. `view` and `projection` are the camera's (the
  // projection jittered as the frame draws); `enabled` false draws everything.
  // `objects` are the frame's transforms (model, model_view_projection, triangle_base).
  void run(const Scene& scene, const float4x4& view, const float4x4& projection, bool enabled,
           const std::vector<ObjectTransforms>& objects);

  // Triangles (scene ids, sorted, disjoint) and mesh vertices (sorted, disjoint) of object `o`.
  const IndexRange* trianglesBegin(size_t o) const { return &triangles_[first_triangle_range_[o]]; }
  const IndexRange* trianglesEnd(size_t o) const {
    return triangles_.data() + first_triangle_range_[o + 1];
  }
  const IndexRange* verticesBegin(size_t o) const { return &vertices_[first_vertex_range_[o]]; }
  const IndexRange* verticesEnd(size_t o) const {
    return vertices_.data() + first_vertex_range_[o + 1];
  }
  bool drawsTriangles(size_t o) const {
    return first_triangle_range_[o + 1] > first_triangle_range_[o];
  }
  const CullCounters& counters() const { return counters_; }

 private:
  std::vector<IndexRange> triangles_, vertices_;
  std::vector<size_t> first_triangle_range_, first_vertex_range_;
  CullCounters counters_;
};

}  // namespace tessera::render
