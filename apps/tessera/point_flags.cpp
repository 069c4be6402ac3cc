#include "point_flags.h"

namespace tessera::cli {

namespace {

// Sizes in pixels: above 0 and up to 64 (a point's splat grows with the square of its size).
std::function<std::string(const std::string&)> pixelsFlag(const std::string& what, float& out) {
  return [what, &out](const std::string& v) -> std::string {
    float pixels;
    if (!parseFloatStrict(v, pixels) || !(pixels > 0.0f && pixels <= 64.0f))
      return "the " + what + " must be a number of pixels above 0 and up to 64, not '" + v + "'";
    out = pixels;
    return "";
  };
}

}  // namespace

void addPointFlags(FlagSet& flags, PointSettings& s, const std::string& line_help) {
  flags.addCustom("point-size", "PIXELS",
                  "the points' diameter in pixels, up to 64 (default 3): point clouds and "
                  "vertices without faces",
                  pixelsFlag("point size", s.points.size));
  flags.addSwitch("point-sprites", &s.points.sprites,
                  "draw points as lit spheres instead of flat discs");
  flags.addCustom("line-width", "PIXELS", line_help, pixelsFlag("width", s.line_width));
}

void applyPointSettings(const PointSettings& s, RenderOptions& options) {
  options.points.size = s.points.size;
  options.points.sprites = s.points.sprites;
  options.line_width = s.line_width;
}

}  // namespace tessera::cli
