// Keyframe animation of the scene graph's node transforms, as glTF 2.0 defines it (3.11 and
// appendix C): each channel drives one node's translation, rotation or scale from a sampler's
// keyframes, stepped, linearly interpolated (rotations by spherical linear interpolation on the
// shorter arc) or by a cubic Hermite spline with the file's tangents. Before the first keyframe a
// channel holds the first value, after the last one the last value.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tessera/base/expected.h>
#include <tessera/math/quat.h>
#include <tessera/math/vec.h>
#include <tessera/scene/mesh.h>

namespace tessera {

struct SceneGraph;

enum class Interpolation : uint8_t { kStep, kLinear, kCubicSpline };
enum class AnimatedProperty : uint8_t { kTranslation, kRotation, kScale };

// Keyframe times (seconds, strictly increasing) and values: translation and scale use x, y, z;
// rotation a quaternion (x, y, z, w). A cubic spline has three values per keyframe, in-tangent,
// value, out-tangent (glTF's layout); the others one.
struct AnimationSampler {
  std::vector<float> times;
  std::vector<float4> values;
  Interpolation interpolation = Interpolation::kLinear;
};

struct AnimationChannel {
  int32_t node = -1;  // into SceneGraph::nodes
  AnimatedProperty property = AnimatedProperty::kTranslation;
  int32_t sampler = -1;  // into Animation::samplers
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;

  // The clip's span: the earliest and latest keyframe time of its samplers (0 and 0 when empty).
  float startTime() const;
  float endTime() const;
  float duration() const { return endTime() - startTime(); }

  // Sets the animated nodes' local translation, rotation or scale at time `t` (seconds, in the
  // file's time line). World matrices are then the caller's: SceneGraph::updateWorld().
  void apply(float t, SceneGraph& graph) const;
};

// World bounds of `graph`'s instances over the clip: the union of the poses at every keyframe
// time and at `samples` evenly spaced times between start and end (a turning cube's corners
// reach past its rest bounds), for framing and near/far planes. Leaves the graph posed at the
// clip's start, world matrices updated.
Bounds clipBounds(const Animation& clip, SceneGraph& graph, int samples = 64);

// An error naming the animation and the sampler or channel when a sampler a channel uses has
// times empty, not finite or
// not strictly increasing, the value count does not match (one or three per keyframe), or an
// index is out of range (`node_count` nodes in the graph).
Expected<void> validateAnimation(const Animation& animation, size_t node_count);

// The sampler's value at time t; `rotation` makes linear interpolation spherical and normalizes
// the result.
float4 sampleAnimation(const AnimationSampler& sampler, float t, bool rotation);

// Spherical linear interpolation from a to b by s in [0, 1], along the shorter arc (b is negated
// when the two are more than 180 degrees apart); a normalized linear blend when they are nearly
// equal, where the sine's division would lose precision.
quat slerp(quat a, quat b, float s);

}  // namespace tessera
