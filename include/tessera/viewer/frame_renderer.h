// The viewer's frames without the window: the orbit camera through the projection F4 picks, the
// anti-aliasing modes, the backend (and why it could not draw, when it could not) and the
// temporal pass. No SDL: tested with any Backend.
#pragma once

#include <string>

#include <tessera/render/backend.h>
#include <tessera/viewer/orbit_camera.h>
#include <tessera/viewer/projection_mode.h>
#include <tessera/viewer/sampling_modes.h>

namespace tessera::viewer {

class FrameRenderer {
 public:
  FrameRenderer(Projection projection, const ViewAngles& angles, const SamplingModes& sampling);

  Projection projection() const { return projection_; }
  // F4: the next projection; the temporal history starts afresh.
  void cycleProjection();
  // Whether frames fill Frame::diagnostics (a diagnostic view is shown); off by default, so
  // that a frame without a view measures nothing.
  void setDiagnostics(bool on) { options_.diagnostics = on; }
  void setShadows(bool on) { options_.shadows.enabled = on; }
  bool shadows() const { return options_.shadows.enabled; }
  bool diagnostics() const { return options_.diagnostics; }
  // How Scene::points and Scene::lines are drawn (RenderOptions::points, line_width).
  void setPointStyle(const PointOptions& points, float line_width) {
    options_.points = points;
    options_.line_width = line_width;
  }
  SamplingModes& sampling() { return sampling_; }
  const SamplingModes& sampling() const { return sampling_; }

  // The scene camera for a width x height frame: `orbit` set to the current projection at its
  // view angle for that shape (viewAngleFor), so that a resize picks the angle again.
  Camera camera(OrbitCamera& orbit, int width, int height);
  // Renders `scene` (its camera from camera() for this size) into `frame` with the anti-aliasing
  // modes' options and the projection, then the temporal pass. A frame the backend could not draw
  // (a device lost, a projection it does not draw) drops the history, and error() says why until
  // a frame draws again. frame.diagnostics is valid only when the backend filled it for this
  // frame. True when the frame drew.
  bool render(Backend& backend, const Scene& scene, int width, int height, Frame& frame);

  const std::string& error() const { return error_; }
  double renderMs() const { return render_ms_; }
  double temporalMs() const { return temporal_ms_; }
  // The last frame's projection for the overlay: "spherical 180°".
  std::string describeProjection() const;

 private:
  Projection projection_;
  ViewAngles angles_;
  float view_angle_ = 0.0f;  // the last camera()'s
  SamplingModes sampling_;
  RenderOptions options_;
  std::string error_;
  double render_ms_ = 0.0, temporal_ms_ = 0.0;
};

}  // namespace tessera::viewer
