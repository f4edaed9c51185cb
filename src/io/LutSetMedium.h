#pragma once
// The medium a LUT set was baked for, from its manifest: what `cloudlut reference scene` and
// `cloudlut render --method raymarch` take with --luts, so that the reference and the ray
// marcher render the medium the tables describe.
#include <filesystem>

#include "core/Medium.h"

namespace cloudlut::io {

// Reads DIR/manifest.json: tables.optical_depth.parameters (density_model, seed,
// extinction_per_m, radius_m) and the scattering tables' first_phase / later_phase
// ({"kind", "param"}, core/Phase.h), which override the default phases when present. FileError
// naming the file and the field when it is missing or malformed. `source` = the manifest's path.
Medium mediumFromLutSet(const std::filesystem::path& dir);

}  // namespace cloudlut::io
