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

// Where a box lies against the view frustum: outside one of its planes, inside all six, or
// neither; for an object, kNotTested where culling does not test it (it has no clusters for its
// mesh, or culling is off): it is drawn whole.
enum class Side : uint8_t { kOutside, kInside, kCrossing, kNotTested };

class FrustumCull {
 public:
  // Room for `objects` objects (classify), before a frame's calls of classify.
  void resize(size_t objects) {
    sides_.resize(objects);
    counts_.resize(objects);
    bases_.resize(objects, kNoBase);
    vertex_bases_.resize(objects, kNoBase);
  }
  // Object o's bounds against the frustum of `mvp` (its model-view-projection), for run, and its
  // mesh's counts; `enabled` false leaves every object to be drawn whole (kNotTested). Objects
  // are independent: the calls for different objects may run at once, on any threads.
  Side classify(const Object& object, size_t o, const float4x4& mvp, bool enabled);
  // The ranges of every object this frame, after every object's classify. `view` and
  // `projection` are the camera's (the projection jittered as the frame draws). `objects` are the
  // frame's transforms: run reads the matrices (model, model_view_projection) of the objects
  // classify did not put outside, and sets every triangle_base (the first scene triangle index of
  // each). Returns the scene's triangle count. Its walk over every object in order reads
  // classify's compact records, and of the objects only those culling tests in part, and writes
  // only the bases that changed since the last frame (a base follows from the meshes before it
  // alone; `objects` is the same vector frame after frame, resized as resize is): reading and
  // writing every object here took a scene of 10,000 instances 0.04 ms (1 worker) to 0.08 ms (2:
  // the lines the other worker had written) a frame.
  size_t run(const Scene& scene, const float4x4& view, const float4x4& projection,
             const CullViewport& viewport, std::vector<ObjectTransforms>& objects);

  // Triangles (scene ids, sorted, disjoint) and mesh vertices (sorted, disjoint) of object `o`.
  const IndexRange* trianglesBegin(size_t o) const { return &triangles_[first_triangle_range_[o]]; }
  const IndexRange* trianglesEnd(size_t o) const {
    return triangles_.data() + first_triangle_range_[o + 1];
  }
  const IndexRange* verticesBegin(size_t o) const { return &vertices_[first_vertex_range_[o]]; }
  const IndexRange* verticesEnd(size_t o) const {
    return vertices_.data() + first_vertex_range_[o + 1];
  }
  // Every object's triangle ranges, in scene order, and how many triangles they hold.
  const std::vector<IndexRange>& triangleRanges() const { return triangles_; }
  size_t drawnTriangles() const {
    size_t total = 0;
    for (const IndexRange& r : triangles_) total += r.end - r.first;
    return total;
  }
  bool drawsTriangles(size_t o) const {
    return first_triangle_range_[o + 1] > first_triangle_range_[o];
  }
  const CullCounters& counters() const { return counters_; }
  void addTo(PipelineStats& stats) const;

  // The vertex stage's jobs (at most `per_job` vertices each) for what the objects draw, and each
  // object's vertex_base in the vertex buffer (objects that draw nothing take no room, and 0),
  // written only where it changed since the last frame, as run's triangle bases. Returns the
  // vertex buffer's size.
  size_t planVertices(size_t per_job, std::vector<ObjectTransforms>& objects,
                      std::vector<VertexJob>& jobs);

 private:
  struct MeshCounts {
    size_t triangles = 0, vertices = 0;
  };
  static constexpr size_t kNoBase = ~size_t{0};
  // Per object: classify's side and mesh counts, and the triangle and vertex bases run and
  // planVertices gave it last (what its ObjectTransforms hold).
  std::vector<Side> sides_;
  std::vector<MeshCounts> counts_;
  std::vector<size_t> bases_, vertex_bases_;
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
