#include <tessera/viewer/orbit_camera.h>

#include <algorithm>
#include <cmath>

namespace tessera::viewer {

namespace {

constexpr float kDegreesPerViewportHeight = 180.0f;
constexpr float kZoomPerStep = 0.9f;

float degrees(float radians_value) {
  return radians_value * (180.0f / kPi);
}

// Unit vector from the target towards the camera.
float3 offsetDirection(float yaw_degrees, float pitch_degrees) {
  const float yaw = radians(yaw_degrees), pitch = radians(pitch_degrees);
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

// The world distance, at `distance` from the eye on the view axis, that a drag across the whole
// viewport height spans horizontally (x) and vertically (y): the image scale at the middle of
// the view, from the mode's ray formula (ARCHITECTURE.md, "Projections") with s = half the angle.
float2 panSpan(Projection mode, float view_angle_degrees, float distance) {
  const float s = radians(view_angle_degrees) * 0.5f;
  switch (mode) {
    case Projection::kPerspective:
      return float2{2.0f * std::tan(s), 2.0f * std::tan(s)} * distance;
    case Projection::kCylindrical:  // longitude u s across, perspective v tan s up
      return float2{2.0f * s, 2.0f * std::tan(s)} * distance;
    case Projection::kSpherical:
    case Projection::kFisheye:  // angle proportional to the distance from the middle
      return float2{2.0f * s, 2.0f * s} * distance;
    case Projection::kStereographic:  // d(2 atan(r tan(s/2)))/dr = 2 tan(s/2) at r = 0
      return float2{4.0f * std::tan(s * 0.5f), 4.0f * std::tan(s * 0.5f)} * distance;
  }
  return {distance, distance};
}

}  // namespace

void OrbitCamera::frame(const Bounds& bounds, float3 direction, float fov_y_degrees, float aspect) {
  fov_y_degrees_ = fov_y_degrees;
  bounds_ = bounds;
  const Camera framed = frameBounds(bounds, direction, {0, 1, 0}, fov_y_degrees, aspect);
  const float3 d = normalize(framed.position - framed.target);
  pose_.target = framed.target;
  pose_.distance = length(framed.position - framed.target);
  pose_.yaw_degrees = degrees(std::atan2(d.x, d.z));
  pose_.pitch_degrees = degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
  home_ = pose_;
  start_camera_.reset();
  at_start_camera_ = false;
}

void OrbitCamera::frameCamera(const Camera& camera, const Bounds& bounds) {
  bounds_ = bounds;
  const float3 forward = normalize(camera.target - camera.position);
  const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-6f);
  const float3 center = bounds.empty() ? camera.target : bounds.center();
  // Turn about the point of the view axis nearest the model's centre (not behind the eye).
  pose_.distance = std::max(dot(center - camera.position, forward), radius * 1e-3f);
  pose_.target = camera.position + forward * pose_.distance;
  pose_.yaw_degrees = degrees(std::atan2(-forward.x, -forward.z));
  pose_.pitch_degrees = degrees(std::asin(std::clamp(-forward.y, -1.0f, 1.0f)));
  if (!camera.orthographic) fov_y_degrees_ = camera.fov_y_degrees;
  home_ = pose_;
  start_camera_ = camera;
  at_start_camera_ = true;
}

void OrbitCamera::orbit(float dx, float dy) {
  at_start_camera_ = false;
  pose_.yaw_degrees -= dx * kDegreesPerViewportHeight;
  pose_.yaw_degrees = std::remainder(pose_.yaw_degrees, 360.0f);
  pose_.pitch_degrees =
      std::clamp(pose_.pitch_degrees + dy * kDegreesPerViewportHeight, -90.0f, 90.0f);
}

void OrbitCamera::pan(float dx, float dy) {
  at_start_camera_ = false;
  const float angle =
      projection_ == Projection::kPerspective ? fov_y_degrees_ : view_angle_degrees_;
  const float2 span = panSpan(projection_, angle, pose_.distance);
  pose_.target = pose_.target - right() * (dx * span.x) + up() * (dy * span.y);
}

void OrbitCamera::zoom(float steps) {
  at_start_camera_ = false;
  const float radius = std::max(bounds_.radius(), 1e-6f);
  pose_.distance =
      std::clamp(pose_.distance * std::pow(kZoomPerStep, steps), radius * 1e-3f, radius * 1e3f);
}

void OrbitCamera::setView(ViewPreset preset) {
  at_start_camera_ = false;
  switch (preset) {
    case ViewPreset::kFront:
      pose_.yaw_degrees = 0.0f, pose_.pitch_degrees = 0.0f;
      break;
    case ViewPreset::kRight:
      pose_.yaw_degrees = 90.0f, pose_.pitch_degrees = 0.0f;
      break;
    case ViewPreset::kTop:
      pose_.yaw_degrees = 0.0f, pose_.pitch_degrees = 90.0f;
      break;
    case ViewPreset::kIsometric:
      // Looking from (1, 1, 1): equal angles to the three axes.
      pose_.yaw_degrees = 45.0f;
      pose_.pitch_degrees = degrees(std::atan(1.0f / std::sqrt(2.0f)));
      break;
  }
}

void OrbitCamera::reset() {
  pose_ = home_;
  at_start_camera_ = start_camera_.has_value();
}

float3 OrbitCamera::position() const {
  return pose_.target + offsetDirection(pose_.yaw_degrees, pose_.pitch_degrees) * pose_.distance;
}

float3 OrbitCamera::forward() const {
  return -offsetDirection(pose_.yaw_degrees, pose_.pitch_degrees);
}

float3 OrbitCamera::right() const {
  const float yaw = radians(pose_.yaw_degrees);
  return {std::cos(yaw), 0.0f, -std::sin(yaw)};
}

// From the angles rather than a world up vector, so straight down (the top view) has an up too.
float3 OrbitCamera::up() const {
  return cross(right(), forward());
}

void OrbitCamera::setProjection(Projection mode, float view_angle_degrees) {
  projection_ = mode;
  view_angle_degrees_ = view_angle_degrees;
}

Camera OrbitCamera::camera() const {
  const bool perspective = projection_ == Projection::kPerspective;
  if (at_start_camera_ && perspective) return *start_camera_;
  Camera c;
  c.position = position();
  c.target = pose_.target;
  c.up = up();
  c.fov_y_degrees = perspective ? fov_y_degrees_ : view_angle_degrees_;
  // Near and far bracket the bounding sphere, wherever panning and zooming have put the camera:
  // along the view direction in perspective, as distances from the eye otherwise (the rule of
  // the CLI's fitDistanceRange: a wide mode sees the sphere's sides too). Near stays a sane
  // fraction of far for depth precision.
  const float radius = bounds_.empty() ? 1.0f : std::max(bounds_.radius(), 1e-6f);
  const float3 center = bounds_.empty() ? pose_.target : bounds_.center();
  const float depth =
      perspective ? dot(center - c.position, forward()) : length(center - c.position);
  c.far_z = std::max(depth + radius * 1.01f, radius * 1e-3f);
  c.near_z = std::max(depth - radius * 1.01f, c.far_z * 1e-4f);
  // An orthographic start camera stays orthographic (the nonlinear modes have their own rays):
  // as high at the turning point as it was, zooming scales it. Near may be 0, not behind the eye.
  if (start_camera_ && start_camera_->orthographic && perspective) {
    c.orthographic = true;
    c.ortho_half_height = start_camera_->ortho_half_height * pose_.distance / home_.distance;
    c.near_z = std::max(depth - radius * 1.01f, 0.0f);
  }
  return c;
}

}  // namespace tessera::viewer
