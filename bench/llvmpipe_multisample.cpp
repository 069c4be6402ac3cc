#include "llvmpipe_multisample.h"

#include <GL/osmesa.h>

namespace tessera::bench {

namespace {

constexpr GLenum kColorFormat = GL_SRGB8_ALPHA8;
constexpr GLenum kDepthFormat = GL_DEPTH_COMPONENT24;  // the OSMesa context's 24 depth bits

// The samples GL gives a renderbuffer of `format` when asked for `samples` (-1: it refused).
GLint samplesGiven(GLenum format, int samples) {
  GLuint renderbuffer = 0;
  glGenRenderbuffers(1, &renderbuffer);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, 1, 1);
  GLint given = -1;
  if (glGetError() == GL_NO_ERROR)
    glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &given);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glDeleteRenderbuffers(1, &renderbuffer);
  while (glGetError() != GL_NO_ERROR) {
  }
  return given;
}

std::string framebufferStatusName(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    default:
      return "status " + std::to_string(status);
  }
}

// Creates a renderbuffer of `samples` (0: single-sample storage) and checks what GL gave.
Expected<GLuint> makeRenderbuffer(GLenum format, int samples, int width, int height,
                                  const char* what) {
  GLuint renderbuffer = 0;
  glGenRenderbuffers(1, &renderbuffer);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  GLint given = -1;
  glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &given);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  if (Expected<void> ok = checkGl(what); !ok) {
    glDeleteRenderbuffers(1, &renderbuffer);
    return ok.error();
  }
  if (given != samples) {
    glDeleteRenderbuffers(1, &renderbuffer);
    return makeError(std::string("OpenGL reference: ") + what + " has " + std::to_string(given) +
                     " samples, not the " + std::to_string(samples) + " asked for");
  }
  return renderbuffer;
}

}  // namespace

std::vector<int> exactSampleCounts() {
  std::vector<int> counts;
  for (int samples : {2, 4, 8})
    if (samplesGiven(kColorFormat, samples) == samples &&
        samplesGiven(kDepthFormat, samples) == samples)
      counts.push_back(samples);
  return counts;
}

Expected<void> MultisampleTarget::allocate(int samples, int width, int height) {
  release();
  // GL 4.5 or ARB_clip_control; libOSMesa does not export it.
  clip_control_ = reinterpret_cast<PFNGLCLIPCONTROLPROC>(OSMesaGetProcAddress("glClipControl"));
  if (!clip_control_)
    return makeError(
        "OpenGL reference: no glClipControl (OpenGL 4.5 or ARB_clip_control), which the "
        "multisampled frame needs to put the standard sample positions where tessera has them");
  auto fail = [&](Error error) -> Expected<void> {
    release();
    return error;
  };
  Expected<GLuint> color = makeRenderbuffer(kColorFormat, samples, width, height,
                                            "the multisampled colour renderbuffer");
  if (!color) return fail(color.error());
  color_ = *color;
  Expected<GLuint> depth =
      makeRenderbuffer(kDepthFormat, samples, width, height, "the multisampled depth renderbuffer");
  if (!depth) return fail(depth.error());
  depth_ = *depth;
  Expected<GLuint> resolved =
      makeRenderbuffer(kColorFormat, 0, width, height, "the resolved colour renderbuffer");
  if (!resolved) return fail(resolved.error());
  resolved_ = *resolved;

  glGenFramebuffers(1, &multisample_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, multisample_fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum multisample_status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glGenFramebuffers(1, &resolve_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolved_);
  const GLenum resolve_status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (Expected<void> ok = checkGl("creating the multisampled framebuffers"); !ok)
    return fail(ok.error());
  if (multisample_status != GL_FRAMEBUFFER_COMPLETE)
    return fail(makeError("OpenGL reference: the " + std::to_string(samples) +
                          "-sample framebuffer is incomplete (" +
                          framebufferStatusName(multisample_status) + ")"));
  if (resolve_status != GL_FRAMEBUFFER_COMPLETE)
    return fail(makeError("OpenGL reference: the resolve framebuffer is incomplete (" +
                          framebufferStatusName(resolve_status) + ")"));
  samples_ = samples;
  width_ = width;
  height_ = height;
  return {};
}

void MultisampleTarget::release() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  for (GLuint* fbo : {&multisample_fbo_, &resolve_fbo_})
    if (*fbo) glDeleteFramebuffers(1, fbo), *fbo = 0;
  for (GLuint* renderbuffer : {&color_, &depth_, &resolved_})
    if (*renderbuffer) glDeleteRenderbuffers(1, renderbuffer), *renderbuffer = 0;
  samples_ = width_ = height_ = 0;
}

void MultisampleTarget::bindForDrawing() const {
  glBindFramebuffer(GL_FRAMEBUFFER, multisample_fbo_);
  glEnable(GL_FRAMEBUFFER_SRGB);  // fragments and the clear colour are linear; stores encode
  // GL gives sample positions from a pixel's lower-left corner, y up: llvmpipe's 4x pattern is
  // the standard one in rows that run bottom-up. With the window origin at the upper left,
  // window y runs down the rows, so the pattern falls as tessera's (y down from the top-left
  // corner) and the rows come out top-down. Facing and the fill rule follow the origin (ARB_
  // clip_control), so culling and the top-left rule stay those of tessera.
  clip_control_(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
}

void MultisampleTarget::resolveAndRead(std::vector<uint32_t>& pixels) const {
  // With GL_FRAMEBUFFER_SRGB on, the blit decodes the sRGB samples, averages them and encodes
  // the result: the resolve in linear light. A resolve blit must not scale, so NEAREST.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, multisample_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  // The frame ends in client memory, as OSMesa's single-sample frame does (OSMesa copies its
  // colour buffer into the caller's at glFinish), and as tessera's ends in Frame::color.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  pixels.resize(static_cast<size_t>(width_) * height_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_FRAMEBUFFER_SRGB);
  clip_control_(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
}

}  // namespace tessera::bench
