// The llvmpipe reference's multisampled frame (tessera bench --vs llvmpipe --msaa N): colour and
// depth renderbuffers with N samples each, drawn into, then resolved by glBlitFramebuffer into a
// single-sample colour renderbuffer that is read back. Colour is sRGB (GL_SRGB8_ALPHA8) with
// GL_FRAMEBUFFER_SRGB on, so the resolve averages in linear light and encodes once, as tessera
// does; the window origin is the upper left (glClipControl), so that the standard sample
// positions fall where tessera's do. Private to llvmpipe_reference.cpp; built only with
// TESSERA_OSMESA. Needs a current context with framebuffer objects (OpenGL 3.0 or
// ARB_framebuffer_object) and clip control (OpenGL 4.5 or ARB_clip_control).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "llvmpipe_programs.h"

namespace tessera::bench {

// The sample counts of 2, 4 and 8 for which the current context makes colour and depth
// renderbuffers with exactly that many samples (GL may round a request up, e.g. llvmpipe gives 4
// for 2). An empty list when it has no multisample renderbuffers.
std::vector<int> exactSampleCounts();

class MultisampleTarget {
 public:
  // (Re)creates the buffers for `samples` (> 1) at width x height. An error when the context
  // gives another sample count or cannot complete either framebuffer; then nothing is allocated.
  Expected<void> allocate(int samples, int width, int height);
  // Deletes the GL objects (the context that allocated them must be current).
  void release();
  bool allocated() const { return multisample_fbo_ != 0; }
  int samples() const { return samples_; }

  // Binds the multisampled framebuffer for drawing and clearing, sRGB encoding on, the window
  // origin at the upper left.
  void bindForDrawing() const;
  // Resolves the samples into the single-sample buffer, reads it into `pixels` (RGBA8 sRGB, R in
  // the low byte, row 0 at the top, as Frame::color) and binds the default framebuffer and the
  // lower-left origin again. Returns when the frame is finished, like glFinish.
  void resolveAndRead(std::vector<uint32_t>& pixels) const;

 private:
  GLuint multisample_fbo_ = 0, resolve_fbo_ = 0;
  GLuint color_ = 0, depth_ = 0, resolved_ = 0;  // renderbuffers
  int samples_ = 0, width_ = 0, height_ = 0;
  PFNGLCLIPCONTROLPROC clip_control_ = nullptr;
};

}  // namespace tessera::bench
