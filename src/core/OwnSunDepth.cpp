#include "core/OwnSunDepth.h"

#include <glm/geometric.hpp>

#include "core/Glsl.h"
#include "core/LastMatter.h"
#include "core/TableLookup.h"

namespace cloudlut {

float ownSunOpticalDepth(const Table4D& opticalDepth, float outerThird, const glm::vec3& x, const glm::vec3& l,
                         float rho) {
  if (glm::dot(x, x) >= 1.0f) return 0.0f;
  const float toSun = glsl::unitSphereExitDistance(x, l);
  const glm::vec3 entry = glm::normalize(x + toSun * l);
  const OpticalDepthSample chord = lookupOpticalDepth(opticalDepth, entry, -l, rho);
  if (!(chord.chordLength > 0.0f)) return 0.0f;
  return glsl::ownSunRamp(chord.opticalDepth, chord.firstMatter, lookupLastMatter(opticalDepth, entry, -l),
                          toSun / chord.chordLength, outerThird);
}

}  // namespace cloudlut
