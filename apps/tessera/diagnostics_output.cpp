#include "diagnostics_output.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include <tessera/io/image_writer.h>
#include <tessera/render/heatmap.h>

namespace tessera::cli {

namespace {

uint16_t clampTo16(double v) {
  return static_cast<uint16_t>(std::clamp(std::lround(v), 0l, 65535l));
}

uint32_t packRgb(uint32_t r, uint32_t g, uint32_t b) {
  return r | (g << 8) | (b << 16) | 0xff000000u;
}

uint8_t unitByte(float v) {
  return std::isnan(v) ? 0 : static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// Every pixel of the frame from `value(pixel index, tile index)`.
template <typename T>
std::vector<T> perPixel(const Frame& frame, const std::function<T(size_t, size_t)>& value) {
  const FrameDiagnostics& d = frame.diagnostics;
  std::vector<T> out(frame.pixelCount());
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const size_t tile = static_cast<size_t>(y / d.tile_size) * d.tile_columns + x / d.tile_size;
      const size_t p = static_cast<size_t>(y) * frame.width + x;
      out[p] = value(p, tile);
    }
  return out;
}

void appendArray(std::string& out, const char* name, size_t n,
                 const std::function<std::string(size_t)>& item) {
  out += "\"";
  out += name;
  out += "\": [";
  for (size_t i = 0; i < n; ++i) {
    if (i) out += ",";
    out += item(i);
  }
  out += "]";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

}  // namespace

const std::vector<std::string>& diagnosticAovNames() {
  static const std::vector<std::string> kNames = {
      "overdraw", "overdraw-heatmap", "occupancy",      "occupancy-heatmap",
      "material", "density",          "tile-occlusion", "tile-edges"};
  return kNames;
}

bool isDiagnosticAov(const std::string& aov) {
  const auto& names = diagnosticAovNames();
  return std::find(names.begin(), names.end(), aov) != names.end();
}

bool needsPixelTests(const std::string& aov) {
  return aov.rfind("overdraw", 0) == 0 || aov.rfind("occupancy", 0) == 0;
}

Expected<void> writeDiagnosticAov(const std::filesystem::path& path, const Frame& frame,
                                  const std::string& aov) {
  const FrameDiagnostics& d = frame.diagnostics;
  const int w = frame.width, h = frame.height;
  if (aov == "overdraw-heatmap" || aov == "occupancy-heatmap") {
    const std::vector<uint32_t> counts =
        aov == "overdraw-heatmap" ? d.overdraw : spreadTiles(d, d.tile_triangles, w, h);
    return io::writePngRgba8(path, w, h, heatmapImage(w, h, counts).data());
  }
  if (aov == "material" || aov == "tile-occlusion") {
    const std::vector<uint32_t> rgb =
        aov == "material"
            ? perPixel<uint32_t>(frame,
                                 [&](size_t p, size_t) { return d.material[p] | 0xff000000u; })
            : perPixel<uint32_t>(frame, [&](size_t, size_t t) {
                return packRgb(unitByte(d.tile_covered[t]), unitByte(d.tile_depth_min[t]),
                               unitByte(d.tile_depth_max[t]));
              });
    return io::writePngRgba8(path, w, h, rgb.data());
  }
  std::function<uint16_t(size_t, size_t)> grey;
  if (aov == "overdraw") grey = [&](size_t p, size_t) { return clampTo16(d.overdraw[p]); };
  if (aov == "occupancy") grey = [&](size_t, size_t t) { return clampTo16(d.tile_triangles[t]); };
  if (aov == "density") grey = [&](size_t p, size_t) { return clampTo16(d.density[p] * 1000.0); };
  if (aov == "tile-edges") grey = [&](size_t, size_t t) { return clampTo16(d.tile_edges[t]); };
  return io::writePngGray16(path, w, h, perPixel<uint16_t>(frame, grey).data());
}

std::string statsFrameJson(const Frame& frame, int index, const std::string& backend) {
  const FrameDiagnostics& d = frame.diagnostics;
  const PipelineCounters& c = d.counters;
  const bool tests = d.has_pixel_tests;
  auto measured = [&](uint64_t v) { return tests ? std::to_string(v) : std::string("null"); };
  std::string out = "{\"frame\": " + std::to_string(index) + ", \"backend\": \"" + backend +
                    "\", \"width\": " + std::to_string(frame.width) +
                    ", \"height\": " + std::to_string(frame.height) + ",\n";
  out += "  \"times_ms\": {\"vertex\": " + number(d.times.vertex_ms) +
         ", \"setup\": " + number(d.times.setup_ms) + ", \"tiles\": " + number(d.times.tiles_ms) +
         ", \"lines\": " + number(d.times.lines_ms) +
         ", \"diagnostics\": " + number(d.times.diagnostics_ms) + "},\n";
  const CullCounts& k = c.culled;
  const bool setup = d.has_setup_counters;
  auto counted = [&](uint64_t v) { return setup ? std::to_string(v) : std::string("null"); };
  const std::string culled = !setup ? std::string("null")
                                    : "{\"invalid\": " + std::to_string(k.invalid) +
                                          ", \"non_finite\": " + std::to_string(k.non_finite) +
                                          ", \"frustum\": " + std::to_string(k.frustum) +
                                          ", \"degenerate\": " + std::to_string(k.degenerate) +
                                          ", \"facing\": " + std::to_string(k.facing) +
                                          ", \"no_pixel\": " + std::to_string(k.no_pixel) +
                                          ", \"clipped_away\": " + std::to_string(k.clipped_away) +
                                          ", \"skipped\": " + std::to_string(k.skipped) +
                                          ", \"total\": " + std::to_string(k.total()) + "}";
  out += "  \"counters\": {\"triangles_in\": " + std::to_string(c.triangles_in) +
         ", \"culled\": " + culled + ", \"triangles_clipped\": " + counted(c.triangles_clipped) +
         ", \"clip_splits\": " + counted(c.clip_splits) +
         ", \"triangles_setup\": " + counted(c.triangles_setup) +
         ", \"triangles_binned\": " + measured(c.triangles_binned) +
         ", \"bin_overflow\": " + measured(c.bin_overflow) +
         ", \"pixels_tested\": " + measured(c.pixels_tested) +
         ", \"pixels_passed\": " + measured(c.pixels_passed) +
         ", \"pixels_shaded\": " + std::to_string(c.pixels_shaded) +
         ", \"tiles\": " + std::to_string(c.tiles) +
         ", \"tiles_empty\": " + std::to_string(c.tiles_empty) +
         ", \"tiles_full\": " + std::to_string(c.tiles_full) +
         ", \"instances_culled\": " + std::to_string(c.instances_culled) +
         ", \"clusters_culled\": " + std::to_string(c.clusters_culled) +
         ", \"clusters_facing\": " + std::to_string(c.clusters_facing) +
         ", \"triangles_skipped\": " + std::to_string(c.triangles_skipped) + "},\n";
  const size_t n = d.tileCount();
  out += "  \"tiles\": {\"size\": " + std::to_string(d.tile_size) +
         ", \"columns\": " + std::to_string(d.tile_columns) +
         ", \"rows\": " + std::to_string(d.tile_rows) + ",\n    ";
  if (tests)
    appendArray(out, "occupancy", n, [&](size_t t) { return std::to_string(d.tile_triangles[t]); });
  else
    out += "\"occupancy\": null";
  out += ",\n    ";
  appendArray(out, "covered", n, [&](size_t t) { return number(d.tile_covered[t]); });
  out += ",\n    ";
  appendArray(out, "depth_min", n, [&](size_t t) { return number(d.tile_depth_min[t]); });
  out += ",\n    ";
  appendArray(out, "depth_max", n, [&](size_t t) { return number(d.tile_depth_max[t]); });
  out += ",\n    ";
  appendArray(out, "edges", n, [&](size_t t) { return std::to_string(d.tile_edges[t]); });
  out += "}}";
  return out;
}

std::string statsFileJson(const std::vector<std::string>& frames) {
  std::string out = "{\"schema\": \"tessera-stats-1\", \"frames\": [\n";
  for (size_t i = 0; i < frames.size(); ++i) out += (i ? ",\n" : "") + frames[i];
  out += "\n]}\n";
  return out;
}

}  // namespace tessera::cli
