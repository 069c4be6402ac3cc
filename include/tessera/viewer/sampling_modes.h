// The viewer's anti-aliasing modes (MSAA, jitter, temporal reprojection) and what they ask of
// each frame: the options to render it with and the temporal pass after it. No SDL.
#pragma once

#include <cstdint>
#include <string>

#include <tessera/render/frame.h>
#include <tessera/render/options.h>
#include <tessera/viewer/temporal.h>

namespace tessera::viewer {

class SamplingModes {
 public:
  SamplingModes(int msaa, bool jitter, bool temporal);

  int msaa() const { return msaa_; }
  bool jitter() const { return jitter_; }
  bool temporal() const { return temporal_; }
  // Shift+F3, F10, Shift+F12. Each starts the history afresh.
  void cycleMsaa();
  void toggleJitter();
  void toggleTemporal();
  // Something other than the camera changed what is drawn (a model, axes, the size): the
  // history no longer shows it.
  void reset() { temporal_pass_.reset(); }
  // The projection the frames are drawn in (F4); a change starts the history afresh. The temporal
  // pass reprojects through a perspective view-projection, so it rests in the other modes (jitter
  // then shows each offset in turn, as without it).
  void setProjection(Projection projection);

  // The sample count and this frame's jitter offset (the next of the cycle, while jitter is on;
  // none otherwise) into `options`, and the depth AOV when the temporal pass needs it.
  void prepare(RenderOptions& options);
  // After the frame rendered with prepare()'s options through `view_projection` (without the
  // jitter): the temporal pass, when it is on with jitter.
  void finish(Frame& frame, const float4x4& view_projection);
  // The image changes with more frames at a still camera: jitter without temporal reprojection
  // shows each offset in turn, and with it the image converges over a cycle and then stays.
  bool wantsAnotherFrame() const;
  // For the stats overlay: "MSAA 4x", "MSAA 4x, jitter", "MSAA 4x, jitter, TAA 5/16" (frames
  // accumulated at a still camera), "MSAA 4x, jitter, TAA"
  // once converged; temporal reprojection without jitter has nothing to blend: "TAA (F10)"; in a
  // nonlinear projection it rests: "TAA: perspective only".
  std::string describe() const;
  // Temporal reprojection acts on the frames: on, with jitter, in perspective.
  bool blending() const { return jitter_ && temporal_ && projection_ == Projection::kPerspective; }

 private:
  int msaa_;
  bool jitter_;
  bool temporal_;
  Projection projection_ = Projection::kPerspective;
  uint32_t jitter_index_ = 0;
  Jitter jitter_offset_;  // the offset of the frame prepare() set up
  TemporalResolver temporal_pass_;
};

}  // namespace tessera::viewer
