// The glTF builder's animations: each of the file's animations into SceneGraph::animations,
// channels retargeted from the file's node indices to the graph's. An animation that cannot be
// played as written (a bad accessor, times that do not increase, a node or sampler index out of
// range) is skipped with a warning naming it: the model itself is sound and still drawn.
// Morph-target weights are not applied (a warning says so).
#include <string>
#include <vector>

#include "gltf_builder.h"
#include "tinygltf_include.h"

namespace tessera::io::gltf {

namespace {

std::string animationName(const tinygltf::Animation& animation, size_t index) {
  return "animation " + std::to_string(index) +
         (animation.name.empty() ? "" : " ('" + animation.name + "')");
}

Expected<Interpolation> interpolationOf(const std::string& name, const std::string& what) {
  if (name.empty() || name == "LINEAR") return Interpolation::kLinear;
  if (name == "STEP") return Interpolation::kStep;
  if (name == "CUBICSPLINE") return Interpolation::kCubicSpline;
  return makeError(what + ": interpolation '" + name +
                   "' is not one of LINEAR, STEP, CUBICSPLINE");
}

}  // namespace

Expected<AnimationSampler> GraphBuilder::readSampler(const tinygltf::AnimationSampler& in,
                                                     bool rotation, const std::string& what) {
  AnimationSampler out;
  Expected<Interpolation> interpolation = interpolationOf(in.interpolation, what);
  if (!interpolation) return interpolation.error();
  out.interpolation = *interpolation;
  Expected<ElementReader> times =
      reader(in.input, "input of " + what, {1}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  if (!times) return times.error();
  // Rotations may be normalized integers (glTF 3.11); translations and scales are floats.
  const std::initializer_list<int> rotation_types = {
      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
  Expected<ElementReader> values =
      rotation ? reader(in.output, "output of " + what, {4}, rotation_types)
               : reader(in.output, "output of " + what, {3}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  if (!values) return values.error();
  out.times.resize(times->count);
  for (size_t k = 0; k < times->count; ++k) out.times[k] = times->component(k, 0);
  out.values.resize(values->count);
  for (size_t k = 0; k < values->count; ++k) {
    float4& v = out.values[k];
    for (int c = 0; c < values->components; ++c) v[c] = values->component(k, c);
  }
  return out;
}

void GraphBuilder::readAnimations() {
  // The graph node of each file node the scene reaches.
  std::vector<int32_t> graph_node(gltf_.nodes.size(), kNoIndex);
  for (size_t i = 0; i < model_.graph.nodes.size(); ++i) {
    const int32_t source = model_.graph.nodes[i].source;
    if (source >= 0 && static_cast<size_t>(source) < graph_node.size())
      graph_node[static_cast<size_t>(source)] = static_cast<int32_t>(i);
  }
  for (size_t a = 0; a < gltf_.animations.size(); ++a) {
    const tinygltf::Animation& in = gltf_.animations[a];
    const std::string name = animationName(in, a);
    Expected<Animation> animation = readAnimation(in, name, graph_node);
    if (!animation) {
      warn(animation.error().message + "; the animation is skipped");
      continue;
    }
    if (Expected<void> valid = validateAnimation(*animation, model_.graph.nodes.size()); !valid) {
      warn(valid.error().message + "; the animation is skipped");
      continue;
    }
    model_.graph.animations.push_back(std::move(*animation));
  }
}

Expected<Animation> GraphBuilder::readAnimation(const tinygltf::Animation& in,
                                                const std::string& name,
                                                const std::vector<int32_t>& graph_node) {
  Animation out;
  out.name = in.name.empty() ? name : in.name;
  // Each sampler is read for the property its first channel animates (rotations are VEC4).
  std::vector<int> read_as(in.samplers.size(), -1);
  for (size_t c = 0; c < in.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = in.channels[c];
    const std::string what = name + " channel " + std::to_string(c);
    const std::string& path = channel.target_path;
    if (path == "weights") {
      warn(what + " animates morph-target weights, which are not applied");
      continue;
    }
    AnimatedProperty property;
    if (path == "translation") property = AnimatedProperty::kTranslation;
    else if (path == "rotation") property = AnimatedProperty::kRotation;
    else if (path == "scale") property = AnimatedProperty::kScale;
    else return makeError(what + ": target path '" + path + "' is not translation, rotation, "
                          "scale or weights");
    if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= in.samplers.size())
      return makeError(what + " names sampler " + std::to_string(channel.sampler) + " of " +
                       std::to_string(in.samplers.size()));
    if (channel.target_node < 0 || static_cast<size_t>(channel.target_node) >= graph_node.size())
      return makeError(what + " targets node " + std::to_string(channel.target_node) +
                       ", but the file has " + std::to_string(graph_node.size()));
    const int32_t node = graph_node[static_cast<size_t>(channel.target_node)];
    if (node == kNoIndex) continue;  // a node outside the scene drawn: nothing to move
    const bool rotation = property == AnimatedProperty::kRotation;
    int& kind = read_as[static_cast<size_t>(channel.sampler)];
    if (kind >= 0 && kind != static_cast<int>(rotation))
      return makeError(what + ": sampler " + std::to_string(channel.sampler) +
                       " drives both a rotation and a translation or scale");
    kind = static_cast<int>(rotation);
    out.channels.push_back({node, property, channel.sampler});
  }
  out.samplers.resize(in.samplers.size());
  for (size_t s = 0; s < in.samplers.size(); ++s) {
    if (read_as[s] < 0) continue;  // no channel of the drawn scene uses it: left empty
    Expected<AnimationSampler> sampler =
        readSampler(in.samplers[s], read_as[s] == 1, name + " sampler " + std::to_string(s));
    if (!sampler) return sampler.error();
    out.samplers[s] = std::move(*sampler);
  }
  return out;
}

}  // namespace tessera::io::gltf
