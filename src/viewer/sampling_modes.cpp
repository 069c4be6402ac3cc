#include <tessera/viewer/sampling_modes.h>

#include <tessera/base/check.h>
#include <tessera/viewer/input_state.h>

namespace tessera::viewer {

SamplingModes::SamplingModes(int msaa, bool jitter, bool temporal)
    : msaa_(msaa), jitter_(jitter), temporal_(temporal) {
  TESSERA_CHECK(isSampleCount(msaa)) << "not a sample count: " << msaa;
}

void SamplingModes::cycleMsaa() {
  msaa_ = nextMsaa(msaa_);
  reset();
}

void SamplingModes::toggleJitter() {
  jitter_ = !jitter_;
  jitter_index_ = 0;
  reset();
}

void SamplingModes::toggleTemporal() {
  temporal_ = !temporal_;
  reset();
}

void SamplingModes::setProjection(Projection projection) {
  if (projection == projection_) return;
  projection_ = projection;
  reset();
}

void SamplingModes::prepare(RenderOptions& options) {
  options.msaa = msaa_;
  jitter_offset_ = jitter_ ? jitterOffset(jitter_index_) : Jitter{};
  if (jitter_) jitter_index_ = (jitter_index_ + 1) % kJitterCycle;
  options.jitter = jitter_offset_;
  options.depth = blending();
}

void SamplingModes::finish(Frame& frame, const float4x4& view_projection) {
  if (blending()) temporal_pass_.resolve(frame, view_projection, jitter_offset_);
}

bool SamplingModes::wantsAnotherFrame() const {
  return jitter_ && !(blending() && temporal_pass_.converged());
}

std::string SamplingModes::describe() const {
  std::string text = "MSAA ";
  text += std::to_string(msaa_);
  text += "x";
  if (jitter_) text += ", jitter";
  if (!temporal_) return text;
  if (projection_ != Projection::kPerspective) return text + ", TAA: perspective only";
  if (!jitter_) return text + ", TAA (F10)";
  text += ", TAA";
  if (!temporal_pass_.converged()) {
    text += " ";
    text += std::to_string(temporal_pass_.stillFrames());
    text += "/";
    text += std::to_string(kJitterCycle);
  }
  return text;
}

}  // namespace tessera::viewer
