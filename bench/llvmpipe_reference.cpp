#include "llvmpipe_reference.h"

#if TESSERA_HAVE_OSMESA

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <thread>

// First: it defines GL_GLEXT_PROTOTYPES before anything includes GL/gl.h.
#include "llvmpipe_multisample.h"
#include "llvmpipe_programs.h"
#include "render/lights.h"

#include <GL/osmesa.h>

#include <tessera/render/sampling.h>
#include <tessera/scene/color.h>

namespace tessera::bench {

namespace {

// Consecutive triangles with one material: a range of indices (indexed objects) or of vertices.
struct DrawRange {
  GLint first = 0;
  GLsizei count = 0;
  uint16_t material = 0;
  ProgramKey key;                    // what the program is compiled for, bar the framebuffer
  const Program* program = nullptr;  // set once the shaders are compiled
  GLuint texture = 0;                // the material's albedo texture when it is sampled
};

struct GpuObject {
  GLuint vertex_buffer = 0, index_buffer = 0;
  bool indexed = false;  // false: a triangle soup carrying face normals (flat shading)
  bool has_uv = false, has_color = false;
  GLintptr normal_offset = 0, uv_offset = 0, color_offset = 0;
  std::vector<DrawRange> ranges;
  std::vector<GLuint> textures;  // per material; 0 where it has no albedo texture
};

void toGl(const float4x4& m, float out[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c * 4 + r] = m(r, c);  // column-major, as GL
}

void toGl(const float3x3& m, float out[9]) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) out[c * 3 + r] = m(r, c);
}

// Points the attributes at the object's buffer (and binds its indices).
void bindVertexArrays(const GpuObject& g) {
  glBindBuffer(GL_ARRAY_BUFFER, g.vertex_buffer);
  glEnableVertexAttribArray(kPosition);
  glVertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(kNormal);
  glVertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, 0,
                        reinterpret_cast<const void*>(g.normal_offset));
  if (g.has_uv) {
    glEnableVertexAttribArray(kUv);
    glVertexAttribPointer(kUv, 2, GL_FLOAT, GL_FALSE, 0,
                          reinterpret_cast<const void*>(g.uv_offset));
  } else {
    glDisableVertexAttribArray(kUv);
  }
  if (g.has_color) {
    glEnableVertexAttribArray(kColor);
    glVertexAttribPointer(kColor, 4, GL_FLOAT, GL_FALSE, 0,
                          reinterpret_cast<const void*>(g.color_offset));
  } else {
    glDisableVertexAttribArray(kColor);
  }
  if (g.indexed) glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.index_buffer);
}

// The process-wide LP_NUM_THREADS llvmpipe was started with (-1: not yet).
int g_llvmpipe_threads = -1;

GLint glWrap(TextureWrap wrap) {
  if (wrap == TextureWrap::kClamp) return GL_CLAMP_TO_EDGE;
  return wrap == TextureWrap::kMirroredRepeat ? GL_MIRRORED_REPEAT : GL_REPEAT;
}

// What uploadGeometry puts in the mesh's buffers.
struct VertexStreams {
  std::vector<float3> positions, normals;
  std::vector<float2> uvs;
  std::vector<float4> colors;
  std::vector<uint32_t> indices;
};

// A mesh's vertex streams as the reference draws them: indexed where it has normals and is not
// flat-shaded, else a triangle soup carrying face normals. Triangles with a non-finite vertex are
// left out, as tessera drops them; `g` gets the flags and the draw ranges, one per run of a
// material.
VertexStreams vertexStreams(const Mesh& mesh, Shading shading, GpuObject& g) {
  const size_t triangles = mesh.triangleCount();
  // Flat shading lights the face normal; a mesh without normals is drawn flat by tessera too.
  g.indexed = shading != Shading::kFlat && !mesh.normals.empty();
  g.has_uv = !mesh.uvs.empty();
  g.has_color = !mesh.colors.empty();
  VertexStreams out;
  auto addToRange = [&](size_t t, GLsizei elements) {
    const uint16_t material = t < mesh.triangle_materials.size() ? mesh.triangle_materials[t] : 0;
    if (g.ranges.empty() || g.ranges.back().material != material) {
      const GLint first = g.ranges.empty() ? 0 : g.ranges.back().first + g.ranges.back().count;
      DrawRange range;
      range.first = first;
      range.material = material;
      g.ranges.push_back(range);
    }
    g.ranges.back().count += elements;
  };
  if (g.indexed) {
    out.positions = mesh.positions;
    out.normals = mesh.normals;
    out.uvs = mesh.uvs;
    out.colors = mesh.colors;
    out.indices.reserve(mesh.indices.size());
  } else {
    out.positions.reserve(triangles * 3);
    out.normals.reserve(triangles * 3);
    if (g.has_uv) out.uvs.reserve(triangles * 3);
    if (g.has_color) out.colors.reserve(triangles * 3);
  }
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t* v = &mesh.indices[t * 3];
    const float3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]], p2 = mesh.positions[v[2]];
    if (!isFinite(p0) || !isFinite(p1) || !isFinite(p2)) continue;
    if (g.indexed) {
      out.indices.insert(out.indices.end(), v, v + 3);
    } else {
      const float3 face = cross(p1 - p0, p2 - p0);  // object space; the shader transforms it
      for (int k = 0; k < 3; ++k) {
        out.positions.push_back(mesh.positions[v[k]]);
        out.normals.push_back(face);
        if (g.has_uv) out.uvs.push_back(mesh.uvs[v[k]]);
        if (g.has_color) out.colors.push_back(mesh.colors[v[k]]);
      }
    }
    addToRange(t, 3);
  }
  return out;
}

// The mesh's streams into one buffer (the positions, then the normals, UVs and colours, each
// tightly packed) and, when indexed, its indices into another.
void uploadGeometry(const Mesh& mesh, Shading shading, GpuObject& g) {
  const VertexStreams s = vertexStreams(mesh, shading, g);
  static_assert(sizeof(float3) == 12 && sizeof(float2) == 8 && sizeof(float4) == 16);
  const GLsizeiptr position_bytes = static_cast<GLsizeiptr>(s.positions.size() * sizeof(float3));
  const GLsizeiptr normal_bytes = static_cast<GLsizeiptr>(s.normals.size() * sizeof(float3));
  const GLsizeiptr uv_bytes = static_cast<GLsizeiptr>(s.uvs.size() * sizeof(float2));
  const GLsizeiptr color_bytes = static_cast<GLsizeiptr>(s.colors.size() * sizeof(float4));
  g.normal_offset = position_bytes;
  g.uv_offset = g.normal_offset + normal_bytes;
  g.color_offset = g.uv_offset + uv_bytes;
  glGenBuffers(1, &g.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, g.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, g.color_offset + color_bytes, nullptr, GL_STATIC_DRAW);
  glBufferSubData(GL_ARRAY_BUFFER, 0, position_bytes, s.positions.data());
  glBufferSubData(GL_ARRAY_BUFFER, g.normal_offset, normal_bytes, s.normals.data());
  if (uv_bytes) glBufferSubData(GL_ARRAY_BUFFER, g.uv_offset, uv_bytes, s.uvs.data());
  if (color_bytes) glBufferSubData(GL_ARRAY_BUFFER, g.color_offset, color_bytes, s.colors.data());
  if (g.indexed) {
    glGenBuffers(1, &g.index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(s.indices.size() * sizeof(uint32_t)), s.indices.data(),
                 GL_STATIC_DRAW);
  }
}

// A material's albedo texture (0 where it has none): sRGB texels decode to linear before
// filtering, as tessera samples them; tessera's own mip levels where it filters trilinearly. GL's
// row 0 is t = 0, tessera's is v = 1: rows go in reversed. (Bench scenes have no texture
// transform.)
GLuint uploadAlbedo(const Material& material) {
  if (!material.albedo || material.albedo->width <= 0 || material.albedo->height <= 0) return 0;
  const Texture& t = *material.albedo;
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  const bool trilinear = material.sampler.filter == TextureFilter::kTrilinear && !t.mips.empty();
  const int levels = trilinear ? t.levelCount() : 1;
  std::vector<uint32_t> rows;
  for (int level = 0; level < levels; ++level) {
    const int w = level == 0 ? t.width : t.mips[static_cast<size_t>(level - 1)].width;
    const int h = level == 0 ? t.height : t.mips[static_cast<size_t>(level - 1)].height;
    const std::vector<uint32_t>& texels =
        level == 0 ? t.texels : t.mips[static_cast<size_t>(level - 1)].texels;
    rows.resize(texels.size());
    for (int y = 0; y < h; ++y)
      std::copy_n(&texels[static_cast<size_t>(h - 1 - y) * w], w,
                  &rows[static_cast<size_t>(y) * w]);
    glTexImage2D(GL_TEXTURE_2D, level, t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, w, h, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, rows.data());
  }
  const GLint filter = material.sampler.filter == TextureFilter::kNearest ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  trilinear ? GL_LINEAR_MIPMAP_LINEAR : filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, glWrap(material.sampler.wrap_s));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, glWrap(material.sampler.wrap_t));
  return texture;
}

}  // namespace

struct LlvmpipeReference::State {
  OSMesaContext context = nullptr;
  std::vector<uint8_t> color;  // the OSMesa colour buffer, RGBA8, rows bottom-up
  int width = 0, height = 0;
  std::string renderer, version;
  int threads = 0;
  ProgramCache programs;
  std::vector<GpuObject> objects;
  size_t light_count = 0;  // the shaders of the current scene are compiled for this many lights
  int tone_curve = -1;     // and for this display transform (ProgramKey::tone_curve)
  int samples = 1;
  MultisampleTarget multisample;   // allocated when samples > 1
  std::vector<uint32_t> resolved;  // the last multisampled frame, resolved, rows top-down

  // Several references may live in one process: GL calls go to the current context.
  void makeCurrent() {
    if (OSMesaGetCurrentContext() != context)
      OSMesaMakeCurrent(context, color.data(), GL_UNSIGNED_BYTE, width, height);
  }

  void releaseScene() {
    for (GpuObject& o : objects) {
      glDeleteBuffers(1, &o.vertex_buffer);
      if (o.index_buffer) glDeleteBuffers(1, &o.index_buffer);
      for (GLuint t : o.textures)
        if (t) glDeleteTextures(1, &t);
    }
    objects.clear();
  }

  // Points every draw range at the program for its key and the current framebuffer, compiling
  // what is missing (now, not in the timed loop).
  Expected<void> linkPrograms() {
    for (GpuObject& g : objects)
      for (DrawRange& range : g.ranges) {
        ProgramKey key = range.key;
        key.framebuffer_encodes_srgb = samples > 1;
        Expected<const Program*> program = programs.get(key);
        if (!program) return program.error();
        range.program = *program;
      }
    return {};
  }

  Expected<void> upload(const Object& object) {
    GpuObject g;
    uploadGeometry(*object.mesh, object.shading, g);
    for (const Material& material : object.materials) g.textures.push_back(uploadAlbedo(material));
    objects.push_back(std::move(g));
    return checkGl("uploading a mesh");
  }

  void draw(const Scene& scene, const Object& object, const GpuObject& g, const float4x4& view,
            const float4x4& projection) {
    if (object.cull == CullMode::kNone) {
      glDisable(GL_CULL_FACE);
    } else {
      glEnable(GL_CULL_FACE);
      glCullFace(object.cull == CullMode::kBack ? GL_BACK : GL_FRONT);
    }
    const float4x4 model = object.transform.matrix();
    float model_view_projection[16], normal_matrix[9];
    toGl(projection * view * model, model_view_projection);
    toGl(normalMatrix(model), normal_matrix);
    // Face normals come from object-space winding: a mirrored object flips them (as tessera).
    const float normal_sign = !g.indexed && determinant(upper3x3(model)) < 0.0f ? -1.0f : 1.0f;
    const int light_count = static_cast<int>(scene.lights.size());
    float light_direction[3 * kMaxLights], light_color[3 * kMaxLights];
    float light_position[4 * kMaxLights], light_params[4 * kMaxLights];
    for (int i = 0; i < light_count; ++i) {
      const render::ShadeLight l = render::shadeLight(scene.lights[i]);
      for (int k = 0; k < 3; ++k) {
        light_direction[3 * i + k] = l.direction[k];
        light_color[3 * i + k] = l.radiance[k];
        light_position[4 * i + k] = l.position[k];
      }
      light_position[4 * i + 3] = static_cast<float>(l.type);
      light_params[4 * i + 0] = l.inv_range4;
      light_params[4 * i + 1] = l.spot_scale;
      light_params[4 * i + 2] = l.spot_offset;
      light_params[4 * i + 3] = 0.0f;
    }
    float model_matrix[16];
    toGl(model, model_matrix);
    // PBR's view vector: render::LightRig::prepare's eye, from the inverse view matrix.
    const float4x4 camera = inverse(view);
    const bool eye_at_infinity = projection(3, 3) != 0.0f;
    const float3 eye = eye_at_infinity ? normalize(camera.col[2].xyz()) : camera.col[3].xyz();

    bindVertexArrays(g);

    for (const DrawRange& range : g.ranges) {
      const Material& material =
          object.materials[range.material < object.materials.size() ? range.material : 0];
      const Program& p = *range.program;
      glUseProgram(p.id);
      glUniformMatrix4fv(p.model_view_projection, 1, GL_FALSE, model_view_projection);
      glUniformMatrix3fv(p.normal_matrix, 1, GL_FALSE, normal_matrix);
      glUniform1f(p.normal_sign, normal_sign);
      glUniform3f(p.ambient, scene.ambient.x, scene.ambient.y, scene.ambient.z);
      if (light_count > 0) {
        glUniform3fv(p.light_direction, light_count, light_direction);
        glUniform3fv(p.light_color, light_count, light_color);
        if (p.light_position >= 0) {
          glUniform4fv(p.light_position, light_count, light_position);
          glUniform4fv(p.light_params, light_count, light_params);
        }
      }
      if (p.model >= 0) glUniformMatrix4fv(p.model, 1, GL_FALSE, model_matrix);
      if (p.eye >= 0) {
        glUniform4f(p.eye, eye.x, eye.y, eye.z, eye_at_infinity ? 0.0f : 1.0f);
        glUniform2f(p.metal_rough, material.metallic, material.roughness);
        glUniform3f(p.emissive, material.emissive_factor.x, material.emissive_factor.y,
                    material.emissive_factor.z);
      }
      if (p.tone_scale >= 0) glUniform1f(p.tone_scale, render::ToneCurve::of(scene).scale);
      glUniform3f(p.base_color, material.base_color.x, material.base_color.y,
                  material.base_color.z);
      if (range.texture) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, range.texture);
        glUniform1i(p.albedo, 0);
      }
      if (g.indexed) {
        glDrawElements(
            GL_TRIANGLES, range.count, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(static_cast<uintptr_t>(range.first) * sizeof(uint32_t)));
      } else {
        glDrawArrays(GL_TRIANGLES, range.first, range.count);
      }
    }
  }
};

bool llvmpipeReferenceBuilt() {
  return true;
}

LlvmpipeReference::LlvmpipeReference() : state_(std::make_unique<State>()) {}

LlvmpipeReference::~LlvmpipeReference() {
  if (state_->context) {
    if (!state_->color.empty()) {
      state_->makeCurrent();
      state_->releaseScene();
      state_->programs.release();
      state_->multisample.release();
    }
    OSMesaDestroyContext(state_->context);
  }
}

Expected<std::unique_ptr<LlvmpipeReference>> LlvmpipeReference::create(int workers) {
  const int threads =
      workers > 0 ? workers : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (g_llvmpipe_threads < 0) {
    // llvmpipe reads this once, when the first context creates its screen.
    setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
    g_llvmpipe_threads = threads;
  } else if (g_llvmpipe_threads != threads) {
    return makeError("llvmpipe already runs " + std::to_string(g_llvmpipe_threads) +
                     " threads in this process; it cannot change to " + std::to_string(threads));
  }
  std::unique_ptr<LlvmpipeReference> reference(new LlvmpipeReference());
  State& s = *reference->state_;
  s.threads = threads;
  if (const std::string missing = loadGlApi(); !missing.empty()) return makeError(missing);
  s.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!s.context) return makeError("OSMesaCreateContextExt failed: no OSMesa context");
  if (Expected<void> sized = reference->setResolution(16, 16); !sized) return sized.error();
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  s.renderer = renderer ? renderer : "unknown";
  s.version = version ? version : "unknown";
  return reference;
}

const std::string& LlvmpipeReference::renderer() const {
  return state_->renderer;
}
const std::string& LlvmpipeReference::version() const {
  return state_->version;
}
bool LlvmpipeReference::isLlvmpipe() const {
  return state_->renderer.find("llvmpipe") != std::string::npos;
}
int LlvmpipeReference::threads() const {
  return state_->threads;
}

Expected<void> LlvmpipeReference::setResolution(int width, int height) {
  State& s = *state_;
  GLint max_width = 0, max_height = 0;
  if (!s.color.empty()) {
    OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_width);
    OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_height);
    if (width > max_width || height > max_height)
      return makeError("OSMesa draws at most " + std::to_string(max_width) + "x" +
                       std::to_string(max_height) + " pixels");
  }
  s.color.assign(static_cast<size_t>(width) * height * 4, 0);
  if (!OSMesaMakeCurrent(s.context, s.color.data(), GL_UNSIGNED_BYTE, width, height))
    return makeError("OSMesaMakeCurrent failed at " + std::to_string(width) + "x" +
                     std::to_string(height));
  s.width = width;
  s.height = height;
  glViewport(0, 0, width, height);
  if (s.samples > 1)
    if (Expected<void> allocated = s.multisample.allocate(s.samples, width, height); !allocated)
      return allocated;
  return checkGl("resizing");
}

Expected<void> LlvmpipeReference::setSamples(int samples) {
  State& s = *state_;
  TESSERA_CHECK(isSampleCount(samples)) << samples << " samples per pixel";
  s.makeCurrent();
  if (samples > 1) {
    const std::vector<int> counts = exactSampleCounts();
    if (std::find(counts.begin(), counts.end(), samples) == counts.end()) {
      std::string supported = "1";
      for (size_t i = 0; i < counts.size(); ++i)
        supported += (i + 1 == counts.size() ? " or " : ", ") + std::to_string(counts[i]);
      return makeError("the OpenGL reference (" + s.renderer + ", " + s.version + ") cannot draw " +
                       std::to_string(samples) +
                       " samples per pixel: its framebuffers take exactly " + supported +
                       " (another count would not be the same work)");
    }
    if (Expected<void> allocated = s.multisample.allocate(samples, s.width, s.height); !allocated)
      return allocated;
  } else {
    s.multisample.release();
  }
  s.samples = samples;
  return s.linkPrograms();
}

int LlvmpipeReference::samples() const {
  return state_->samples;
}

Expected<void> LlvmpipeReference::setScene(const Scene& scene) {
  State& s = *state_;
  s.makeCurrent();
  if (scene.lights.size() > static_cast<size_t>(kMaxLights))
    return makeError("the OpenGL reference takes at most " + std::to_string(kMaxLights) +
                     " lights; the scene has " + std::to_string(scene.lights.size()));
  if (Expected<void> drawable = checkPbrMaps(scene); !drawable) return drawable;
  s.releaseScene();
  s.light_count = scene.lights.size();
  const render::ToneCurve tone = render::ToneCurve::of(scene);
  s.tone_curve = tone.active() ? static_cast<int>(tone.mapping) : -1;
  const int light_count = static_cast<int>(scene.lights.size());
  const bool local_lights =
      std::any_of(scene.lights.begin(), scene.lights.end(),
                  [](const Light& l) { return l.type != LightType::kDirectional; });
  for (const Object& object : scene.objects) {
    TESSERA_CHECK(object.mesh) << "an object without a mesh";
    if (Expected<void> uploaded = s.upload(object); !uploaded) return uploaded;
    GpuObject& g = s.objects.back();
    for (DrawRange& range : g.ranges) {
      const size_t m = range.material < object.materials.size() ? range.material : 0;
      range.texture = g.has_uv ? g.textures[m] : 0;
      range.key = {object.shading, range.texture != 0, g.has_color, object.cull != CullMode::kBack,
                   light_count};
      range.key.local_lights = local_lights;
      range.key.tone_curve = s.tone_curve;
    }
  }
  if (Expected<void> linked = s.linkPrograms(); !linked) return linked;
  return checkGl("uploading the scene");
}

void LlvmpipeReference::render(const Scene& scene) {
  State& s = *state_;
  TESSERA_CHECK(scene.objects.size() == s.objects.size())
      << "render() needs the scene given to setScene()";
  s.makeCurrent();
  TESSERA_CHECK(scene.lights.size() == s.light_count)
      << "the shaders were compiled for " << s.light_count << " lights";
  const render::ToneCurve tone = render::ToneCurve::of(scene);
  TESSERA_CHECK((tone.active() ? static_cast<int>(tone.mapping) : -1) == s.tone_curve)
      << "the shaders were compiled for another tone curve";
  const float4 bg = scene.background;
  if (s.samples > 1) {
    s.multisample.bindForDrawing();
    glClearColor(bg.x, bg.y, bg.z, 1.0f);  // linear: the sRGB framebuffer encodes it
  } else {
    glClearColor(static_cast<float>(encodeSrgb8(bg.x)) / 255.0f,
                 static_cast<float>(encodeSrgb8(bg.y)) / 255.0f,
                 static_cast<float>(encodeSrgb8(bg.z)) / 255.0f, 1.0f);
  }
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glFrontFace(GL_CCW);  // counter-clockwise in NDC is front-facing, as in tessera
  const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
  const float4x4 view = scene.camera.view();
  const float4x4 projection = scene.camera.projection(aspect);
  for (size_t i = 0; i < scene.objects.size(); ++i)
    s.draw(scene, scene.objects[i], s.objects[i], view, projection);
  if (s.samples > 1) {
    s.multisample.resolveAndRead(s.resolved);
  } else {
    glFinish();
  }
}

void LlvmpipeReference::readColor(std::vector<uint32_t>& rgba) const {
  State& s = *state_;
  s.makeCurrent();
  if (s.samples > 1) {  // read back by render(), top-down
    TESSERA_CHECK(s.resolved.size() == static_cast<size_t>(s.width) * s.height)
        << "readColor() needs a render() at the current resolution";
    rgba = s.resolved;
    return;
  }
  std::vector<uint32_t> bottom_up(static_cast<size_t>(s.width) * s.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, s.width, s.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  rgba.resize(bottom_up.size());
  // GL's row 0 is the bottom one; tessera's the top one.
  for (int y = 0; y < s.height; ++y)
    std::copy_n(&bottom_up[static_cast<size_t>(s.height - 1 - y) * s.width], s.width,
                &rgba[static_cast<size_t>(y) * s.width]);
}

}  // namespace tessera::bench

#else  // !TESSERA_HAVE_OSMESA

namespace tessera::bench {

struct LlvmpipeReference::State {};

bool llvmpipeReferenceBuilt() {
  return false;
}

LlvmpipeReference::LlvmpipeReference() = default;
LlvmpipeReference::~LlvmpipeReference() = default;

Expected<std::unique_ptr<LlvmpipeReference>> LlvmpipeReference::create(int) {
  return makeError(
      "this tessera was built without OSMesa, so it has no llvmpipe reference: install Debian's "
      "libosmesa6-dev and reconfigure (CMake option TESSERA_OSMESA)");
}

const std::string& LlvmpipeReference::renderer() const {
  static const std::string kNone = "none";
  return kNone;
}
const std::string& LlvmpipeReference::version() const {
  return renderer();
}
bool LlvmpipeReference::isLlvmpipe() const {
  return false;
}
int LlvmpipeReference::threads() const {
  return 0;
}
Expected<void> LlvmpipeReference::setScene(const Scene&) {
  return makeError("no OSMesa");
}
Expected<void> LlvmpipeReference::setResolution(int, int) {
  return makeError("no OSMesa");
}
Expected<void> LlvmpipeReference::setSamples(int) {
  return makeError("no OSMesa");
}
int LlvmpipeReference::samples() const {
  return 1;
}
void LlvmpipeReference::render(const Scene&) {}
void LlvmpipeReference::readColor(std::vector<uint32_t>& rgba) const {
  rgba.clear();
}

}  // namespace tessera::bench

#endif
