// The viewer's orbit camera: a point it turns about (the target), a distance and two angles,
// driven by drags and wheel steps. Knows nothing of windows or SDL.
#pragma once

#include <optional>

#include <tessera/render/projection.h>
#include <tessera/scene/mesh.h>
#include <tessera/scene/scene.h>

namespace tessera::viewer {

// The fixed views of f3d's number keys (with +Y up): 1 front, 3 right, 7 top, 9 isometric.
enum class ViewPreset { kFront, kRight, kTop, kIsometric };

class OrbitCamera {
 public:
  // Frames `bounds` (the whole model fits the narrower field of view) from `direction`, which
  // points from the model towards the camera, and makes this the view that reset() returns to.
  void frame(const Bounds& bounds, float3 direction, float fov_y_degrees, float aspect);
  // Starts from `camera` (a camera of the file, or an orthographic framing: --camera-index,
  // --camera-orthographic) and makes it the view that reset() returns to. Until the camera moves,
  // camera() is exactly this one (in perspective mode); moving turns it about the point on its
  // view axis nearest the bounds' centre, keeping its field of view or, orthographic, its height
  // at that distance.
  void frameCamera(const Camera& camera, const Bounds& bounds);

  // Turns about the target by fractions of the viewport height: a drag across the whole height
  // turns 180 degrees. The model follows the pointer: dragging right turns it to the right,
  // dragging down tips its top towards the viewer. Elevation stops at straight above and below.
  void orbit(float dx, float dy);
  // Moves the camera and target in the view plane so that the point at the target's depth
  // follows the pointer (at the middle of the view, in the nonlinear modes); dx, dy in fractions
  // of the viewport height, y down.
  void pan(float dx, float dy);
  // Positive steps move closer (the wheel pushed away from the user); each step is 10%.
  void zoom(float steps);
  // Keeps the target and distance, looks from one of the preset directions.
  void setView(ViewPreset preset);
  // Back to the framing of the last frame().
  void reset();

  // The projection camera() is for: perspective (the default) draws with frame()'s angle; another
  // mode with `view_angle_degrees`, and takes near and far as distances from the eye.
  void setProjection(Projection mode, float view_angle_degrees);
  Projection projection() const { return projection_; }

  // The scene camera, with near and far fitted to the framed bounds: along the view axis in
  // perspective, as distances from the eye in the nonlinear modes (where depth is the distance
  // along the ray).
  Camera camera() const;

  float3 target() const { return pose_.target; }
  float distance() const { return pose_.distance; }
  float yawDegrees() const { return pose_.yaw_degrees; }
  float pitchDegrees() const { return pose_.pitch_degrees; }
  float3 position() const;
  // Unit vectors of the current view (right-handed: right x up = -forward).
  float3 forward() const;
  float3 right() const;
  float3 up() const;

 private:
  struct Pose {
    float3 target{0, 0, 0};
    float distance = 5.0f;
    float yaw_degrees = 0.0f;    // about +Y; 0 looks down -Z from +Z, 90 looks from +X
    float pitch_degrees = 0.0f;  // elevation above the XZ plane, in [-90, 90]
  };

  Pose pose_;
  Pose home_;
  // frameCamera()'s camera, and whether the pose is still its own (no move since it or reset()).
  std::optional<Camera> start_camera_;
  bool at_start_camera_ = false;
  float fov_y_degrees_ = 50.0f;
  Projection projection_ = Projection::kPerspective;
  float view_angle_degrees_ = 50.0f;  // the nonlinear mode's
  Bounds bounds_;                     // what near and far must enclose
};

}  // namespace tessera::viewer
