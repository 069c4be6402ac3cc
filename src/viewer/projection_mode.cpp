#include <tessera/viewer/projection_mode.h>

#include <cstdio>
#include <iterator>

namespace tessera::viewer {

Projection nextProjection(Projection p) {
  const size_t count = std::size(kProjections);
  for (size_t i = 0; i < count; ++i)
    if (kProjections[i] == p) return kProjections[(i + 1) % count];
  return Projection::kPerspective;
}

float viewAngleFor(Projection p, float aspect, const ViewAngles& angles) {
  if (p == Projection::kPerspective) return angles.perspective;
  if (angles.requested && checkViewAngle(p, *angles.requested, aspect).empty())
    return *angles.requested;
  return defaultViewAngle(p, aspect);
}

std::string describeProjection(Projection p, float view_angle_degrees) {
  char text[64];
  std::snprintf(text, sizeof text, "%s %.4g\u00b0", projectionName(p),
                static_cast<double>(view_angle_degrees));
  return text;
}

}  // namespace tessera::viewer
