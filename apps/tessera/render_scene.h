// tessera render's scene: the model file loaded and made a scene with its camera, lights, surface
// and axes as the flags ask (cmd_render.cpp renders it).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <tessera/scene/graph.h>
#include <tessera/scene/scene.h>

#include "render_settings.h"

namespace tessera::cli {

// The model as a scene with its camera, lights and axes, and the model's bounds. An exit status
// other than kExitOk when something fails (printed, or usage_error's); kExitOk after --info's
// listing too.
int loadScene(const RenderSettings& s, const std::filesystem::path& model_path, Scene& scene,
              Bounds& bounds, SceneGraph& graph,
              const std::function<int(const std::string&)>& usage_error);

}  // namespace tessera::cli
