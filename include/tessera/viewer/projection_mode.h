// The viewer's projection (F4) and the view angle each mode draws with. No SDL.
#pragma once

#include <optional>
#include <string>

#include <tessera/render/projection.h>

namespace tessera::viewer {

// F4's cycle, in the order of kProjections: perspective -> cylindrical -> spherical ->
// stereographic -> fisheye -> perspective.
Projection nextProjection(Projection p);

// The view angles the user gave, in degrees.
struct ViewAngles {
  float perspective = 50.0f;       // perspective's angle, which also frames the model
  std::optional<float> requested;  // -fov when given: any nonlinear mode that accepts it takes it
};

// The vertical view angle mode `p` draws with on a window of this aspect (width / height):
// perspective's angle in perspective; in another mode the requested angle where checkViewAngle
// accepts it for that mode and aspect, else the mode's default (defaultViewAngle), so that a
// resize or a mode the angle does not fit still shows a valid picture.
float viewAngleFor(Projection p, float aspect, const ViewAngles& angles);

// For the overlay: "perspective 50°", "spherical 180°", "cylindrical 112.5°".
std::string describeProjection(Projection p, float view_angle_degrees);

}  // namespace tessera::viewer
