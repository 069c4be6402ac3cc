// The flags that say how points and lines are drawn, shared by render, view and bench:
// --point-size PIXELS, --point-sprites and --line-width PIXELS (docs/rendering.md).
#pragma once

#include <string>

#include <tessera/render/options.h>

#include "flags.h"

namespace tessera::cli {

struct PointSettings {
  PointOptions points;      // size and sprites from the flags; the colour stays the default
  float line_width = 1.0f;  // Scene::lines (and, in render, the polygon edges)
};

// Adds the three flags; `line_help` says what --line-width widens in this subcommand.
void addPointFlags(FlagSet& flags, PointSettings& settings, const std::string& line_help);

// Copies the point size, sprites and line width into `options`.
void applyPointSettings(const PointSettings& settings, RenderOptions& options);

}  // namespace tessera::cli
