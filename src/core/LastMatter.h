#pragma once
// The last matter of a chord of the reference particle: the distance from the chord's entry S
// along v to the last point where the normalised density ρ̂ reaches the first-matter threshold,
// as a fraction of the chord (dimensionless, [0, 1]). The optical-depth table stores the first
// matter only (channel 1); the last matter of the chord (S, v) is the first matter of the same
// chord entered from its exit E = S + L·v along −v, counted back from the exit:
//   lastMatter(S, v) = max(1 − firstMatter(E, −v), firstMatter(S, v))
// (the max keeps it at or after the first matter; 1 when the chord holds no matter).
// A chord's matter lies in [firstMatter, lastMatter]; the renderer's volumes ramp each chord's
// optical depth over that stretch and its mean scattering point lies in it (docs/LIGHTING.md).
#include <glm/vec3.hpp>

#include "core/Table4D.h"

namespace cloudlut {

// lastMatter(S, v) from the optical-depth table, interpolated as the renderer interpolates it
// (Table4D::sample at the reversed chord). S on the unit sphere, v a unit direction into it.
float lookupLastMatter(const Table4D& opticalDepth, const glm::vec3& S, const glm::vec3& v);

// The optical-depth table with a third channel, last_matter = lookupLastMatter at every node
// (channels 0 and 1 copied; a table without a first-matter channel gets first matter 0 and last
// matter 1). The renderer derives the same channel on the GPU when it loads the tables
// (render/LastMatterTexture, last_matter.comp.glsl); this is the tests' reference for it.
// Channels beyond the first two of the input are dropped.
Table4D withLastMatterChannel(const Table4D& opticalDepth);

}  // namespace cloudlut
