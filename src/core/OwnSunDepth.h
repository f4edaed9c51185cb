#pragma once
// A particle's own optical depth toward the sun at a point inside it, from the optical-depth
// table, as the renderer's sun volume lays it (docs/LIGHTING.md, "The particle's own core
// shadow"): the CPU side of the own term's core shadow, for the angular closure's model and the
// tests.
#include <glm/vec3.hpp>

#include "core/Table4D.h"

namespace cloudlut {

// τ_own (dimensionless) at point x of the unit sphere (particle space) of a particle of density
// scale rho lit from the unit direction l (toward the sun): the particle's chord through x along
// the sun, entered on its sunward side in direction −l (seed eq. 1 from the table:
// ρ·σ·L·T̄), laid from its first matter to its last matter with the share outerThird in each
// outer third (ownSunRamp, cloudlut_shading.glsl; the table's chordOuterThird,
// core/TableLookup.h; core/LastMatter.h), read at x. 0 outside the sphere.
float ownSunOpticalDepth(const Table4D& opticalDepth, float outerThird, const glm::vec3& x, const glm::vec3& l,
                         float rho);

}  // namespace cloudlut
