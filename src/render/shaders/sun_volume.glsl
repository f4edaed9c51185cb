// sun_volume.glsl — the sun optical-depth volume: the one definition of its grid and of how a
// particle's chord is laid along a column, shared by the splat and integration passes
// (sun_volume_build.comp.glsl), the particle shader that samples it, and the C++ that checks it
// (render/SunVolumeGrid.h compiles this file through GLM).
//
// The grid. Columns are sun rays: a world point x maps to grid coordinates g = G·x + o (G, o
// the affine map of one cascade, sunVolumeToGrid), where g.z = w is the slice coordinate along
// a world axis (y for cloudscapes, the axis most aligned with the sun otherwise), increasing
// toward the sun, and (g.x, g.y) = (u, v) the column, sheared along the sun direction so that
// a line of constant (u, v) is parallel to l. Texel (i, j, k) holds, at the node g = (i, j, k),
//     τ(g) = ∫ σ_ext ds  from that point toward the sun, out of the grid  (dimensionless),
// the optical depth of every particle in front of it along the sun ray.
//
// A particle's contribution to one column (seed §4.1 table, eq. 1): the chord of the column's
// sun ray through the particle has the optical depth τ_c = ρ·σ·L·T̄ of the optical-depth table,
// laid linearly along the column from the chord's first matter (table channel 1) on its sun
// side to its last matter: τ rises from 0 at w = wFirst to τ_c at w = wFar (< wFirst) and stays
// τ_c beyond. This ramp is written as its second difference in w (two weighted deltas, split
// between the integer slices about each end) and recovered exactly at the integer slices by a
// double prefix sum from the sun side (see sunVolumeRampAt).

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Optical depth of the ramp of one chord at slice coordinate w: τ_c·clamp((wFirst − w)/(wFirst − wFar), 0, 1).
CLOUDLUT_FN float sunVolumeRampAt(float tauChord, float wFirst, float wFar, float w) {
  float span = max(wFirst - wFar, 1e-6f);
  return tauChord * clamp((wFirst - w) / span, 0.0f, 1.0f);
}

// Weight of the ramp's delta at wEdge carried by integer slice k (linear split between
// floor(wEdge) and floor(wEdge) + 1): the double prefix sum of these weights times the ramp's
// slope reproduces max(0, wEdge − k) exactly at every integer k.
CLOUDLUT_FN vec2 sunVolumeDeltaSplit(float wEdge) {
  float f = wEdge - floor(wEdge);
  return vec2(1.0f - f, f);
}
