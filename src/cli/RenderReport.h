#pragma once
// `cloudlut render`'s report of one frame: the file written, the stage times (ms) and what the
// renderer did that a user may want to know (lighting kept, downscale, volume blending's tiles
// and fragment lists, loop-budget cuts, sun-volume overflow) on stdout; warnings on stderr.
#include <filesystem>
#include <string>

#include "render/Renderer.h"

namespace cloudlut::cli {

void printFrameReport(const std::filesystem::path& file, const render::Image& image, const render::RenderStats& stats,
                      const render::RenderSettings& settings, double setupSeconds, const std::string& contextDescription);

}  // namespace cloudlut::cli
