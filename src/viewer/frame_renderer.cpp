#include <tessera/viewer/frame_renderer.h>

#include <chrono>

namespace tessera::viewer {

using Clock = std::chrono::steady_clock;

FrameRenderer::FrameRenderer(Projection projection, const ViewAngles& angles,
                             const SamplingModes& sampling)
    : projection_(projection), angles_(angles), sampling_(sampling) {
  sampling_.setProjection(projection_);
  // Colour and lines only: the temporal pass asks for depth when it needs it.
  options_.depth = false;
  options_.ids = false;
  options_.lines = true;
}

void FrameRenderer::cycleProjection() {
  projection_ = nextProjection(projection_);
  sampling_.setProjection(projection_);
}

Camera FrameRenderer::camera(OrbitCamera& orbit, int width, int height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  view_angle_ = viewAngleFor(projection_, aspect, angles_);
  orbit.setProjection(projection_, view_angle_);
  return orbit.camera();
}

bool FrameRenderer::render(Backend& backend, const Scene& scene, int width, int height,
                           Frame& frame) {
  options_.width = width;
  options_.height = height;
  options_.projection = projection_;
  sampling_.prepare(options_);
  // A backend that does not fill the diagnostics must not leave an earlier frame's behind.
  frame.diagnostics.valid = false;
  const Clock::time_point start = Clock::now();
  backend.render(scene, options_, frame);
  const Clock::time_point rendered_at = Clock::now();
  render_ms_ = std::chrono::duration<double, std::milli>(rendered_at - start).count();
  if (Expected<void> rendered = backend.lastResult(); !rendered) {
    error_ = rendered.error().message;
    sampling_.reset();
    return false;
  }
  error_.clear();
  // The view-projection the backend used, as the CPU renderer builds it, without the jitter (the
  // temporal pass takes it in perspective only).
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  sampling_.finish(frame, scene.camera.projection(aspect) * scene.camera.view());
  temporal_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - rendered_at).count();
  return true;
}

std::string FrameRenderer::describeProjection() const {
  return viewer::describeProjection(projection_, view_angle_);
}

}  // namespace tessera::viewer
