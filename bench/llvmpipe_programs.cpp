#include "llvmpipe_programs.h"

#include "bench/shared_glsl.h"

namespace tessera::bench {

namespace {

// The lighting of tessera's shading stage (src/render/lights.h, setup.cpp and shade.cpp) in
// GLSL 1.20 (4.50 compatibility with PBR or a tone curve, whose shared source needs it): Lambert
// from directional, point and spot lights plus ambient, on the world normal (point and spot lights,
// LOCAL_LIGHTS, at the interpolated world position). Flat and Gouraud light the vertices (flat ones
// carry the face normal, and are lit at each corner where tessera lights the centroid) and
// interpolate albedo times light; smooth (Phong) interpolates albedo and normal and lights each
// fragment; the texture multiplies per fragment; back faces that are drawn are lit from the
// viewer's side; sRGB encoding comes once, last: in the fragment shader, or (multisampled) in the
// sRGB framebuffer, after the resolve has averaged. PBR interpolates base colour, normal and world
// position and evaluates glTF's BRDF per fragment with the formulas of the Vulkan backends
// (pbr_brdf.glsl); the tone curve, when asked for, comes before the encode.
//
// The lights and irradiance(), in both stages (each compiles its own copy).
constexpr const char* kLighting = R"(
uniform vec3 u_ambient;
#if LIGHT_COUNT > 0
uniform vec3 u_light_direction[LIGHT_COUNT];
uniform vec3 u_light_color[LIGHT_COUNT];  // radiance: colour x intensity
#endif
#if defined(LOCAL_LIGHTS) && LIGHT_COUNT > 0
uniform vec4 u_light_position[LIGHT_COUNT];  // w: tessera::LightType
uniform vec4 u_light_params[LIGHT_COUNT];
#endif
#ifdef WORLD_POSITION
varying vec3 v_world;
#else
#define v_world vec3(0.0)
#endif
vec3 irradiance(vec3 n, vec3 p) {
  vec3 e = u_ambient;
#if LIGHT_COUNT > 0
  for (int i = 0; i < LIGHT_COUNT; ++i) {
#ifdef LOCAL_LIGHTS
    // Point and spot (w = 1, 2): 1/d^2, the range window, the cone (src/render/lights.h).
    if (u_light_position[i].w > 0.5) {
      vec3 l = u_light_position[i].xyz - p;
      float d2 = dot(l, l);
      vec3 u = l * inversesqrt(d2);
      vec4 k = u_light_params[i];  // 1 / range^4, the spot's scale and offset
      float window = clamp(1.0 - d2 * d2 * k.x, 0.0, 1.0);
      float t = clamp(-dot(u_light_direction[i], u) * k.y + k.z, 0.0, 1.0);
      e += u_light_color[i] * max(dot(n, u) * window * t * t / d2, 0.0);
      continue;
    }
#endif
    e += u_light_color[i] * max(-dot(n, u_light_direction[i]), 0.0);
  }
#endif
  return e;
}
)";

constexpr const char* kVertexShader = R"(
attribute vec3 a_position;
attribute vec3 a_normal;
attribute vec2 a_uv;
attribute vec4 a_color;
uniform mat4 u_model_view_projection;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform float u_normal_sign;
uniform vec3 u_base_color;
varying vec2 v_uv;
varying vec3 v_front;  // albedo, times the lighting when it is per vertex
varying vec3 v_back;   // the same for a back face (two-sided lighting)
varying vec3 v_normal;

void main() {
  gl_Position = u_model_view_projection * vec4(a_position, 1.0);
#ifdef WORLD_POSITION
  v_world = (u_model * vec4(a_position, 1.0)).xyz;
#endif
#ifdef HAS_UV
  v_uv = a_uv;
#endif
  vec3 albedo = u_base_color;
#ifdef HAS_COLOR
  albedo *= a_color.rgb;
#endif
#if defined(LIT_PER_VERTEX) || defined(LIT_PER_PIXEL)
  vec3 n = normalize(u_normal_matrix * a_normal) * u_normal_sign;
#endif
#ifdef LIT_PER_VERTEX
  v_front = albedo * irradiance(n, v_world);
#ifdef TWO_SIDED
  v_back = albedo * irradiance(-n, v_world);
#endif
#else
  v_front = albedo;
  v_back = albedo;
#endif
#ifdef LIT_PER_PIXEL
  v_normal = n;
#endif
}
)";

// render::shadePbr without an environment (the bench has none), after pbr_brdf.glsl: the uniform
// ambient, every light in order, then the emission; n the unit normal, p the world position.
constexpr const char* kPbrShading = R"(
uniform vec4 u_eye;          // w = 1: the eye's world position; w = 0: the direction towards it
uniform vec2 u_metal_rough;  // the material's metallic and perceptual roughness
uniform vec3 u_emissive;

// render::viewVector
vec3 viewVector(vec3 p) {
  if (u_eye.w == 0.0) return u_eye.xyz;
  precise vec3 d = u_eye.xyz - p;
  precise float len2 = (d.x * d.x + d.y * d.y) + d.z * d.z;
  precise float inv = len2 > 0.0 ? 1.0 / sqrt(len2) : 0.0;
  precise vec3 v = d * inv;
  return v;
}

vec3 shadePbr(PbrLobes s, vec3 n, vec3 p) {
  const vec3 v = viewVector(p);
  const float nv = abs(dot3(n, v));
  precise vec3 c = pbrAmbient(s, u_ambient, 1.0, nv);
#if LIGHT_COUNT > 0
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    vec3 l = -u_light_direction[i];
    float nl = dot3(n, l);
    float f = nl;
#ifdef LOCAL_LIGHTS
    if (u_light_position[i].w > 0.5) {
      // render::localAttenuation: 1 / d^2, the range window, the cone.
      precise vec3 d = u_light_position[i].xyz - p;
      precise float d2 = (d.x * d.x + d.y * d.y) + d.z * d.z;
      precise float inv_d = 1.0 / sqrt(d2);
      precise vec3 u = d * inv_d;
      const vec4 k = u_light_params[i];  // 1 / range^4, the spot's scale and offset
      precise float window = clamp(1.0 - d2 * d2 * k.x, 0.0, 1.0);
      precise float t = clamp(-dot3(u_light_direction[i], u) * k.y + k.z, 0.0, 1.0);
      l = u;
      nl = dot3(n, l);
      precise float lit = nl * ((window * (t * t)) / d2);
      f = lit;
    }
#endif
    if (!(nl > 0.0 && f > 0.0)) continue;
    c = c + pbrResponse(s, n, v, l, nl, nv) * (u_light_color[i] * f);
  }
#endif
  precise vec3 result = c + u_emissive;
  return result;
}
)";

constexpr const char* kFragmentShader = R"(
uniform sampler2D u_albedo;
uniform float u_tone_scale;
varying vec2 v_uv;
varying vec3 v_front;
varying vec3 v_back;
varying vec3 v_normal;

// IEC 61966-2-1.
vec3 encodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
#ifdef TWO_SIDED
  vec3 color = gl_FrontFacing ? v_front : v_back;
#else
  vec3 color = v_front;
#endif
#ifdef HAS_UV
  color *= texture2D(u_albedo, v_uv).rgb;
#endif
#ifdef LIT_PER_PIXEL
  vec3 n = normalize(v_normal);
#ifdef TWO_SIDED
  if (!gl_FrontFacing) n = -n;
#endif
#ifdef PBR
  color = shadePbr(pbrLobes(color, u_metal_rough.x, u_metal_rough.y), n, v_world);
#else
  color *= irradiance(n, v_world);
#endif
#endif
#ifdef TONE_CURVE
  color = toneCurve(color, u_tone_scale, uint(TONE_CURVE));
#endif
#ifdef FRAMEBUFFER_ENCODES_SRGB
  gl_FragColor = vec4(color, 1.0);  // the sRGB colour buffer clamps and encodes
#else
  gl_FragColor = vec4(encodeSrgb(color), 1.0);
#endif
}
)";

const char* glErrorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "a GL error";
  }
}

Expected<GLuint> compileShader(GLenum type, const std::string& source) {
  GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    return makeError(std::string("OpenGL reference: shader compile failed: ") + log);
  }
  return shader;
}

}  // namespace

Expected<void> checkPbrMaps(const Scene& scene) {
  for (const Object& object : scene.objects) {
    if (object.shading != Shading::kPbr || !object.mesh || object.mesh->uvs.empty()) continue;
    for (const Material& m : object.materials) {
      const char* map = m.metallic_roughness ? "metallic-roughness"
                        : m.normal           ? "normal"
                        : m.occlusion        ? "occlusion"
                        : m.emissive         ? "emissive"
                                             : nullptr;
      if (map)
        return makeError(std::string("the OpenGL reference draws PBR materials from their factors "
                                     "and base colour texture only; this scene has a ") +
                         map + " map");
    }
  }
  return {};
}

Expected<void> checkGl(const char* what) {
  GLenum error = glGetError();
  if (error == GL_NO_ERROR) return {};
  while (glGetError() != GL_NO_ERROR) {
  }
  return makeError(std::string("OpenGL reference: ") + what + " failed with " + glErrorName(error));
}

Expected<const Program*> ProgramCache::get(const ProgramKey& key) {
  auto found = programs_.find(key);
  if (found != programs_.end()) return &found->second;
  const bool pbr = key.shading == Shading::kPbr, tone = key.tone_curve >= 0;
  std::string defines = pbr || tone ? "#version 450 compatibility\n" : "#version 120\n";
  defines += "#define LIGHT_COUNT " + std::to_string(key.light_count) + "\n";
  if (key.shading == Shading::kFlat || key.shading == Shading::kGouraud)
    defines += "#define LIT_PER_VERTEX\n";
  if (key.shading == Shading::kPhong || key.shading == Shading::kPbr)
    defines += "#define LIT_PER_PIXEL\n";
  if (key.has_uv) defines += "#define HAS_UV\n";
  if (key.has_color) defines += "#define HAS_COLOR\n";
  if (key.two_sided) defines += "#define TWO_SIDED\n";
  if (key.framebuffer_encodes_srgb) defines += "#define FRAMEBUFFER_ENCODES_SRGB\n";
  if (key.local_lights) defines += "#define LOCAL_LIGHTS\n";
  if (pbr || (key.local_lights && key.light_count > 0)) defines += "#define WORLD_POSITION\n";
  // The shared GLSL marks its arithmetic `precise` so that the Vulkan backends keep the CPU's
  // bits; the reference lets llvmpipe contract and reorder as it would an ordinary shader (the
  // images stay within 1/255: bench_reference_test), so it is not timed with a handicap.
  if (pbr || tone) defines += "#define precise\n";
  if (pbr) defines += "#define PBR\n";
  if (tone) defines += "#define TONE_CURVE " + std::to_string(key.tone_curve) + "\n";
  Expected<GLuint> vs = compileShader(GL_VERTEX_SHADER, defines + kLighting + kVertexShader);
  if (!vs) return vs.error();
  std::string fragment = defines + kLighting;
  if (pbr) fragment += std::string(kPbrBrdfGlsl) + kPbrShading;
  if (tone) fragment += kToneCurveGlsl;
  Expected<GLuint> fs = compileShader(GL_FRAGMENT_SHADER, fragment + kFragmentShader);
  if (!fs) {
    glDeleteShader(*vs);
    return fs.error();
  }
  Program p;
  p.id = glCreateProgram();
  glAttachShader(p.id, *vs);
  glAttachShader(p.id, *fs);
  glBindAttribLocation(p.id, kPosition, "a_position");
  glBindAttribLocation(p.id, kNormal, "a_normal");
  glBindAttribLocation(p.id, kUv, "a_uv");
  glBindAttribLocation(p.id, kColor, "a_color");
  glLinkProgram(p.id);
  glDeleteShader(*vs);
  glDeleteShader(*fs);
  GLint ok = 0;
  glGetProgramiv(p.id, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(p.id, sizeof log, nullptr, log);
    glDeleteProgram(p.id);
    return makeError(std::string("OpenGL reference: shader link failed: ") + log);
  }
  p.model_view_projection = glGetUniformLocation(p.id, "u_model_view_projection");
  p.normal_matrix = glGetUniformLocation(p.id, "u_normal_matrix");
  p.normal_sign = glGetUniformLocation(p.id, "u_normal_sign");
  p.ambient = glGetUniformLocation(p.id, "u_ambient");
  p.light_direction = glGetUniformLocation(p.id, "u_light_direction");
  p.light_color = glGetUniformLocation(p.id, "u_light_color");
  p.light_position = glGetUniformLocation(p.id, "u_light_position");
  p.light_params = glGetUniformLocation(p.id, "u_light_params");
  p.model = glGetUniformLocation(p.id, "u_model");
  p.base_color = glGetUniformLocation(p.id, "u_base_color");
  p.albedo = glGetUniformLocation(p.id, "u_albedo");
  p.eye = glGetUniformLocation(p.id, "u_eye");
  p.metal_rough = glGetUniformLocation(p.id, "u_metal_rough");
  p.emissive = glGetUniformLocation(p.id, "u_emissive");
  p.tone_scale = glGetUniformLocation(p.id, "u_tone_scale");
  return &programs_.emplace(key, p).first->second;
}

void ProgramCache::release() {
  for (auto& [key, program] : programs_) glDeleteProgram(program.id);
  programs_.clear();
}

}  // namespace tessera::bench
