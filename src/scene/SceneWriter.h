#pragma once
// A particle scene as the JSON document of docs/SCENE_FORMAT.md (the inverse of parseScene): the
// file `cloudlut render --dump-particles` writes, which --particles, `reference scene` and
// `bake --for-scene` read back.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/Scene.h"

namespace cloudlut::scene {

// The document of `particles` seen with `view` (camera, sun and sky fields) and, when enabled,
// the detail noise `detail`; numbers written with the 9 significant digits that carry a float
// exactly.
nlohmann::json sceneDocument(const std::vector<Particle>& particles, const View& view, const std::string& description,
                             const DetailNoise& detail = {});

// The document as text (one particle per line).
std::string sceneText(const nlohmann::json& document);

}  // namespace cloudlut::scene
