// Frustum and cluster culling, before the vertex stage: every object with clusters
// (Object::clusters) is tested by its bounds against the view frustum, then each of its clusters
// by its bounds and, when the object culls a face, by its normal cone. What survives is a list of
// triangle ranges per object (setup reads only those) and of vertex ranges (the vertex stage
// transforms only those). Conservative: a rejected triangle is one the per-triangle tests would
// have dropped (wholly outside one of the planes the outcodes test, or facing away by so much
// that snapping its vertices cannot turn it: see facesAway), so the image does not change by a
// pixel. Objects without clusters are drawn whole.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tessera/math/math.h>
#include <tessera/render/cpu_renderer.h>
#include <tessera/scene/scene.h>

#include "render/vertex.h"

namespace tessera::render {

struct IndexRange {
  size_t first, end;
};

// A run of vertices of one object for the vertex stage.
struct VertexJob {
  uint32_t object;
  size_t first;
  size_t count;
};

struct CullCounters {
  size_t instances_culled = 0, clusters_culled = 0, clusters_facing = 0;
  size_t triangles_in_culled_instances = 0, triangles_in_culled_clusters = 0;
};

struct CullViewport {
  int width = 0, height = 0;  // pixels
};

class FrustumCull {
 public:
  // The ranges of every object this frame. `view` and `projection` are the camera's (the
  // projection jittered as the frame draws); `enabled` false draws everything.
  // `objects` are the frame's transforms (model, model_view_projection, triangle_base).
  void run(const Scene& scene, const float4x4& view, const float4x4& projection,
           const CullViewport& viewport, bool enabled,
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
  void addTo(PipelineStats& stats) const;

  // The vertex stage's jobs (at most `per_job` vertices each) for what the objects draw, and each
  // object's vertex_base in the vertex buffer (objects that draw nothing take no room). Returns
  // the vertex buffer's size.
  size_t planVertices(const Scene& scene, size_t per_job, std::vector<ObjectTransforms>& objects,
                      std::vector<VertexJob>& jobs) const;

 private:
  std::vector<IndexRange> triangles_, vertices_;
  std::vector<size_t> first_triangle_range_, first_vertex_range_;
  CullCounters counters_;
};

// Walks the triangle ranges an object keeps, forwards.
class TriangleRuns {
 public:
  TriangleRuns(const FrustumCull& cull, size_t object)
      : range_(cull.trianglesBegin(object)), end_(cull.trianglesEnd(object)) {}
  // Moves `t` to the first kept triangle at or after it (to `stop` when there is none before
  // it) and returns the end of its run, at most `stop`.
  size_t next(size_t& t, size_t stop) {
    while (range_ != end_ && range_->end <= t) ++range_;
    if (range_ == end_ || range_->first >= stop) return t = stop;
    t = std::max(t, range_->first);
    return std::min(range_->end, stop);
  }

 private:
  const IndexRange* range_;
  const IndexRange* end_;
};

}  // namespace tessera::render
