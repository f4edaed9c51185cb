#pragma once
// A contact sheet of a 4D table: one tile per depth slice of its 3D texture (axis 0 across,
// axis 1 down inside a tile; tiles laid out with axis 2 across and axis 3 down), false-coloured
// with a perceptual map, with axis labels and a colour scale. Non-finite values are magenta,
// so NaNs, seams and banding stand out.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/Table4D.h"

namespace cloudlut::io {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // rows top first
};

struct ContactSheetOptions {
  int channel = 0;
  std::optional<std::pair<float, float>> range;  // colour-scale range; default the finite min..max
  int maxWidth = 4096;                            // tiles are subsampled along axis 2 beyond this
};

RgbImage drawContactSheet(const Table4D& table, const std::string& title, const ContactSheetOptions& options);

}  // namespace cloudlut::io
