// How the triangles' image lies over the background: a transparent background (Scene::background
// with alpha below 1: `--no-background`) and the surface's opacity (RenderOptions::opacity:
// `--opacity`). Every backend composites after its triangles and before its line and point passes.
#pragma once

#include <cstdint>
#include <span>

#include <tessera/math/vec.h>
#include <tessera/render/frame.h>
#include <tessera/render/options.h>

namespace tessera {

struct Scene;

// Whether compositeOverBackground changes anything for this scene and these options: a background
// alpha below 1 or an opacity below 1. A backend then fills the coverage AOV, which it reads.
bool needsComposite(const Scene& scene, const RenderOptions& options);
// `options` with the coverage AOV on when needsComposite says the frame needs it.
RenderOptions withCompositeInputs(const Scene& scene, const RenderOptions& options);

// Each pixel's colour R, the triangles resolved over the background B in linear light with
// coverage c (Frame::coverage / 255), becomes o R + (1 - o) B, which is what the surface at
// opacity o over the background gives: c o S + (1 - c o) B. Its alpha becomes c o + a (1 - c o),
// a the background's alpha. Only the nearest surface is seen through: what lies behind it is not
// drawn. With a transparent black background (--no-background: 0, 0, 0, 0) the colour is then
// the surface's premultiplied by its alpha; straightAlpha undoes that for a PNG.
void compositeOverBackground(float4 background, float opacity, Frame& frame);

// With scene.environment_background (and an environment): every pixel's background becomes the
// environment's radiance along the pixel centre's view ray (projection.h's rays for
// options.projection, turned into the world by the camera; an orthographic camera's rays are all
// its view axis), in the proportion compositeOverBackground left the plain background in: with
// coverage c and opacity o, R becomes R + (1 - c o) (E - B). Run after compositeOverBackground.
void compositeEnvironment(const Scene& scene, const RenderOptions& options, Frame& frame);

// What every backend runs after its triangles: compositeOverBackground and then
// compositeEnvironment, where needsComposite says the frame needs them.
void compositeFrame(const Scene& scene, const RenderOptions& options, Frame& frame);

// RGBA8 pixels whose colour is premultiplied by alpha in linear light, made straight as PNG
// stores them: each channel decoded, divided by alpha and encoded again; alpha 0 gives black.
void straightAlpha(std::span<uint32_t> pixels);

}  // namespace tessera
