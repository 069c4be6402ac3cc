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
}

void OrbitCamera::orbit(float dx, float dy) {
  pose_.yaw_degrees -= dx * kDegreesPerViewportHeight;
  pose_.yaw_degrees = std::remainder(pose_.yaw_degrees, 360.0f);
  pose_.pitch_degrees =
      std::clamp(pose_.pitch_degrees + dy * kDegreesPerViewportHeight, -90.0f, 90.0f);
}

void OrbitCamera::pan(float dx, float dy) {
  // The world height that the viewport spans at the target's depth.
  const float span = 2.0f * pose_.distance * std::tan(radians(fov_y_degrees_) * 0.5f);
  pose_.target = pose_.target - right() * (dx * span) + up() * (dy * span);
}

void OrbitCamera::zoom(float steps) {
  const float radius = std::max(bounds_.radius(), 1e-6f);
  pose_.distance =
      std::clamp(pose_.distance * std::pow(kZoomPerStep, steps), radius * 1e-3f, radius * 1e3f);
}

void OrbitCamera::setView(ViewPreset preset) {
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

Camera OrbitCamera::camera() const {
  Camera c;
  c.position = position();
  c.target = pose_.target;
  c.up = up();
  c.fov_y_degrees = fov_y_degrees_;
  // Near and far bracket the bounding sphere along the view direction, wherever panning and
  // zooming have put the camera; near stays a sane fraction of far for depth precision.
  const float radius = bounds_.empty() ? 1.0f : std::max(bounds_.radius(), 1e-6f);
  const float3 center = bounds_.empty() ? pose_.target : bounds_.center();
  const float depth = dot(center - c.position, forward());
  c.far_z = std::max(depth + radius * 1.01f, radius * 1e-3f);
  c.near_z = std::max(depth - radius * 1.01f, c.far_z * 1e-4f);
  return c;
}

}  // namespace tessera::viewer
