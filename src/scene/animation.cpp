#include <tessera/scene/animation.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <tessera/scene/graph.h>

namespace tessera {

namespace {

float4 lerp4(float4 a, float4 b, float s) {
  return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, a.z + (b.z - a.z) * s,
          a.w + (b.w - a.w) * s};
}

quat toQuat(float4 v) { return {v.x, v.y, v.z, v.w}; }
float4 toFloat4(quat q) { return {q.x, q.y, q.z, q.w}; }

float4 normalizedRotation(float4 v) { return toFloat4(normalize(toQuat(v))); }

// glTF appendix C: p(s) = (2s^3 - 3s^2 + 1) v0 + td (s^3 - 2s^2 + s) b0 + (-2s^3 + 3s^2) v1
// + td (s^3 - s^2) a1, with b0 the out-tangent of keyframe k and a1 the in-tangent of k + 1.
float4 hermite(float4 v0, float4 b0, float4 v1, float4 a1, float td, float s) {
  const float s2 = s * s, s3 = s2 * s;
  const float h00 = 2 * s3 - 3 * s2 + 1, h10 = td * (s3 - 2 * s2 + s);
  const float h01 = -2 * s3 + 3 * s2, h11 = td * (s3 - s2);
  return {h00 * v0.x + h10 * b0.x + h01 * v1.x + h11 * a1.x,
          h00 * v0.y + h10 * b0.y + h01 * v1.y + h11 * a1.y,
          h00 * v0.z + h10 * b0.z + h01 * v1.z + h11 * a1.z,
          h00 * v0.w + h10 * b0.w + h01 * v1.w + h11 * a1.w};
}

std::string samplerName(const Animation& animation, size_t index) {
  return "animation '" + animation.name + "' sampler " + std::to_string(index);
}

Expected<void> validateSampler(const Animation& animation, size_t index) {
  const AnimationSampler& s = animation.samplers[index];
  if (s.times.empty()) return makeError(samplerName(animation, index) + " has no keyframes");
  for (size_t k = 0; k < s.times.size(); ++k) {
    if (!std::isfinite(s.times[k]))
      return makeError(samplerName(animation, index) + ": keyframe " + std::to_string(k) +
                       "'s time is not a finite number");
    if (k > 0 && !(s.times[k] > s.times[k - 1]))
      return makeError(samplerName(animation, index) + ": keyframe times must increase, but " +
                       std::to_string(s.times[k]) + " (keyframe " + std::to_string(k) +
                       ") follows " + std::to_string(s.times[k - 1]));
  }
  const size_t per_key = s.interpolation == Interpolation::kCubicSpline ? 3 : 1;
  if (s.values.size() != s.times.size() * per_key)
    return makeError(samplerName(animation, index) + " has " + std::to_string(s.values.size()) +
                     " values for " + std::to_string(s.times.size()) + " keyframes (" +
                     std::to_string(per_key) + " per keyframe expected)");
  return {};
}

}  // namespace

quat slerp(quat a, quat b, float s) {
  float d = a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
  if (d < 0.0f) {  // the shorter arc: q and -q are the same rotation
    b = {-b.x, -b.y, -b.z, -b.w};
    d = -d;
  }
  if (d > 0.9995f) return normalize(toQuat(lerp4(toFloat4(a), toFloat4(b), s)));
  const float theta = std::acos(std::min(d, 1.0f));
  const float sin_theta = std::sin(theta);
  const float wa = std::sin((1.0f - s) * theta) / sin_theta;
  const float wb = std::sin(s * theta) / sin_theta;
  return {wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w};
}

float4 sampleAnimation(const AnimationSampler& sampler, float t, bool rotation) {
  const std::vector<float>& times = sampler.times;
  const bool cubic = sampler.interpolation == Interpolation::kCubicSpline;
  // The keyframe's value: the middle of a cubic spline's three.
  auto value = [&](size_t k) { return sampler.values[cubic ? 3 * k + 1 : k]; };
  auto finish = [&](float4 v) { return rotation ? normalizedRotation(v) : v; };
  if (times.empty()) return rotation ? float4{0, 0, 0, 1} : float4{0, 0, 0, 0};
  if (!(t > times.front())) return finish(value(0));
  if (t >= times.back()) return finish(value(times.size() - 1));
  // times[k] <= t < times[k + 1]
  const size_t k =
      static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const float td = times[k + 1] - times[k];
  const float s = (t - times[k]) / td;
  switch (sampler.interpolation) {
    case Interpolation::kStep:
      return finish(value(k));
    case Interpolation::kLinear:
      if (rotation) return toFloat4(slerp(toQuat(value(k)), toQuat(value(k + 1)), s));
      return lerp4(value(k), value(k + 1), s);
    case Interpolation::kCubicSpline:
      return finish(hermite(value(k), sampler.values[3 * k + 2], value(k + 1),
                            sampler.values[3 * (k + 1)], td, s));
  }
  return finish(value(k));
}

float Animation::startTime() const {
  float start = 0.0f;
  bool any = false;
  for (const AnimationSampler& s : samplers) {
    if (s.times.empty()) continue;
    start = any ? std::min(start, s.times.front()) : s.times.front();
    any = true;
  }
  return start;
}

float Animation::endTime() const {
  float end = 0.0f;
  for (const AnimationSampler& s : samplers)
    if (!s.times.empty()) end = std::max(end, s.times.back());
  return end;
}

void Animation::apply(float t, SceneGraph& graph) const {
  for (const AnimationChannel& channel : channels) {
    if (channel.node < 0 || static_cast<size_t>(channel.node) >= graph.nodes.size()) continue;
    if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= samplers.size()) continue;
    const AnimationSampler& sampler = samplers[static_cast<size_t>(channel.sampler)];
    Transform& local = graph.nodes[static_cast<size_t>(channel.node)].local;
    const bool rotation = channel.property == AnimatedProperty::kRotation;
    const float4 v = sampleAnimation(sampler, t, rotation);
    switch (channel.property) {
      case AnimatedProperty::kTranslation:
        local.translation = {v.x, v.y, v.z};
        break;
      case AnimatedProperty::kRotation:
        local.rotation = toQuat(v);
        break;
      case AnimatedProperty::kScale:
        local.scale = {v.x, v.y, v.z};
        break;
    }
  }
}

Bounds clipBounds(const Animation& clip, SceneGraph& graph, int samples) {
  Bounds bounds;
  auto add = [&](float t) {
    clip.apply(t, graph);
    graph.updateWorld();
    const Bounds pose = graph.bounds();
    if (!pose.empty()) {
      bounds.add(pose.min);
      bounds.add(pose.max);
    }
  };
  const float start = clip.startTime(), end = clip.endTime();
  for (const AnimationSampler& sampler : clip.samplers)
    for (float t : sampler.times) add(t);
  for (int i = 0; i <= samples; ++i)
    add(start + (end - start) * static_cast<float>(i) / static_cast<float>(std::max(samples, 1)));
  clip.apply(start, graph);
  graph.updateWorld();
  return bounds;
}

Expected<void> validateAnimation(const Animation& animation, size_t node_count) {
  for (size_t i = 0; i < animation.channels.size(); ++i) {
    const AnimationChannel& c = animation.channels[i];
    const std::string name = "animation '" + animation.name + "' channel " + std::to_string(i);
    if (c.sampler < 0 || static_cast<size_t>(c.sampler) >= animation.samplers.size())
      return makeError(name + " names sampler " + std::to_string(c.sampler) + " of " +
                       std::to_string(animation.samplers.size()));
    if (c.node < 0 || static_cast<size_t>(c.node) >= node_count)
      return makeError(name + " names node " + std::to_string(c.node) + " of " +
                       std::to_string(node_count));
  }
  // The samplers the channels use (a file may list others, which are never read).
  std::vector<char> used(animation.samplers.size(), 0);
  for (const AnimationChannel& c : animation.channels) used[static_cast<size_t>(c.sampler)] = 1;
  for (size_t i = 0; i < animation.samplers.size(); ++i) {
    if (!used[i]) continue;
    if (auto valid = validateSampler(animation, i); !valid) return valid;
  }
  return {};
}

}  // namespace tessera
