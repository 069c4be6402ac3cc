// The llvmpipe reference's OpenGL side that is not about the scene: the GLSL programs that
// implement tessera's shading (GLSL 1.20 for the Lambert modes; 4.50 compatibility for PBR and the
// tone curves, whose source they share with the Vulkan backends), one per combination of what a
// draw needs, and the GL error check.
// Private to llvmpipe_reference.cpp; built only with TESSERA_OSMESA. Needs a current context.
#pragma once

#include <map>
#include <string>
#include <tuple>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
// Last of the GL headers: the calls below go through the pointers it loads.
#include "bench/gl_api.h"

#include <tessera/base/expected.h>
#include <tessera/scene/scene.h>

namespace tessera::bench {

// Fixed attribute locations, bound before linking.
enum AttributeLocation : GLuint { kPosition = 0, kNormal = 1, kUv = 2, kColor = 3 };

// What a program is compiled for.
struct ProgramKey {
  Shading shading = Shading::kGouraud;
  bool has_uv = false, has_color = false, two_sided = false;
  int light_count = 0;
  // true: the fragment shader writes linear colour and an sRGB framebuffer encodes it (so that a
  // multisample resolve averages in linear light); false: the shader encodes sRGB itself.
  bool framebuffer_encodes_srgb = false;
  bool local_lights = false;  // a point or spot light: world positions are interpolated
  // The display transform after the shading (render/tone.h): -1 none, else the exposure's scale
  // (a uniform) then this tessera::ToneMapping curve (0: the scale alone).
  int tone_curve = -1;
  auto tie() const {
    return std::tie(shading, has_uv, has_color, two_sided, light_count, framebuffer_encodes_srgb,
                    local_lights, tone_curve);
  }
  bool operator<(const ProgramKey& o) const { return tie() < o.tie(); }
};

struct Program {
  GLuint id = 0;
  GLint model_view_projection, normal_matrix, normal_sign, ambient, light_direction, light_color,
      base_color, albedo, light_position = -1, light_params = -1, model = -1;
  // PBR: the eye (w = 1) or the direction towards it (w = 0), metallic and roughness, emission.
  GLint eye = -1, metal_rough = -1, emissive = -1;
  GLint tone_scale = -1;  // 2^exposure, when tone_curve >= 0
};

// The programs of one context, compiled on first use and kept until release().
class ProgramCache {
 public:
  Expected<const Program*> get(const ProgramKey& key);
  void release();

 private:
  std::map<ProgramKey, Program> programs_;
};

// The programs' PBR reads a material's factors and its base colour texture: an error when a PBR
// object of `scene` has one of glTF's other maps, which the reference would leave out (not the
// same work or image as tessera's).
Expected<void> checkPbrMaps(const Scene& scene);

// glGetError after `what`: an error naming it and the GL error, or success. Clears every error.
Expected<void> checkGl(const char* what);

}  // namespace tessera::bench
