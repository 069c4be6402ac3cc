// Temporal anti-aliasing for the viewer: each jittered frame is blended with the history
// reprojected through the previous frame's view-projection, so that a moving camera gets
// supersampled edges over time and a still one converges to the accumulated image. Works on the
// colour and depth of any backend's Frame; knows nothing of windows.
#pragma once

#include <cstdint>
#include <vector>

#include <tessera/math/mat.h>
#include <tessera/render/frame.h>
#include <tessera/render/sampling.h>

namespace tessera::viewer {

// Jitter offsets in one cycle: frame i of a run takes jitterOffset(i % kJitterCycle).
inline constexpr int kJitterCycle = 16;

// Where the point at the centre of pixel (x, y) was in the previous frame, in window
// coordinates (pixel centres at +0.5), and its depth there as clip w (view depth for a
// perspective projection). `depth`: the frame's window z at the pixel (from its jittered sample:
// within a pixel of the centre, the same surface); +inf (nothing drawn) is taken at the far
// plane. `reprojection` is previous view-projection * inverse(current), both without jitter.
// The centre, not the jittered sample: the history is the unjittered image.
struct Reprojected {
  float x = 0, y = 0;
  float view_depth = 0;
};
Reprojected reprojectPixel(const float4x4& reprojection, const float4x4& inverse_current, int x,
                           int y, float depth, int width, int height);

class TemporalResolver {
 public:
  // Frames a pixel's history counts at most while the camera moves: the current frame weighs at
  // least 1/8, which follows an orbit closely while it still averages 8 jitter offsets.
  static constexpr int kMovingHistory = 8;

  // Forget the history: the next frame starts afresh (a model load, a change of sample count or
  // of anything else drawn; a resize resets by itself).
  void reset() { valid_ = false; }

  // Blends `frame` (RGBA8 sRGB colour and the depth AOV, both needed), rendered with `jitter`
  // through `view_projection` (without the jitter), with the history, and writes the result back
  // into frame.color. Alpha is kept.
  //  - Camera moved (any bit of the matrix): the history is reprojected through the current depth,
  //    clamped to the 3x3 neighbourhood of the current frame in YCoCg, and blended in linear light
  //    (weight 1/n of the current frame, n up to kMovingHistory). A pixel whose point was off
  //    screen or hidden in the previous frame (no depth near its own) starts again from the
  //    current frame.
  //  - Camera still: the frames since it stopped are summed; the image is
  //    (sum + (kJitterCycle - n) * image_when_it_stopped) / kJitterCycle, so after kJitterCycle
  //    frames it is exactly their average (the Accumulator's, for a whole cycle of offsets), and
  //    it then stays (converged()).
  void resolve(Frame& frame, const float4x4& view_projection, Jitter jitter);

  // The camera has been still for a whole cycle: the image is the accumulated average and no
  // further frame changes it.
  bool converged() const { return valid_ && still_frames_ >= kJitterCycle; }
  // Frames summed at the current camera (1 on the frame the camera moved or history restarted).
  int stillFrames() const { return valid_ ? still_frames_ : 0; }

 private:
  void start(const Frame& frame);
  void blendMoving(Frame& frame, const float4x4& view_projection);
  void accumulateStill();
  void keepDepth(const Frame& frame, const float4x4& view_projection, Jitter jitter);
  void encodeInto(Frame& frame);

  bool valid_ = false;
  int width_ = 0, height_ = 0;
  float4x4 previous_view_projection_;
  int still_frames_ = 0;
  // Linear RGB per pixel. While the camera moves, next_ is the image being made (reprojection
  // reads history_); while it is still, next_ holds the image shown when it stopped.
  std::vector<float3> current_;  // this frame
  std::vector<float3> history_;  // the last image shown
  std::vector<float3> next_;
  std::vector<float3> still_sum_;      // the frames since the camera stopped
  std::vector<float> previous_depth_;  // the last frame's view depth (clip w); +inf for nothing
  std::vector<uint8_t> count_, next_count_;  // frames in each pixel's history, to kMovingHistory
  std::vector<uint32_t> next_color_;         // the encoded image being made
  std::vector<uint32_t> converged_color_;    // the converged image, encoded once
};

}  // namespace tessera::viewer
