// sun_volume.glsl — the sun optical-depth volume: the one definition of its grid and of how a
// particle's chord is laid along a column, shared by the splat and integration passes
// (sun_volume_build.comp.glsl) and the shaders that sample it (sun_volume_sampling.glsl); the
// grid's C++ side is render/SunVolumeGrid.h.
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
// laid along the column from the chord's first matter (table channel 1) on its sun side, at
// w = wFirst, to its last matter, at wFar < wFirst, as the particle holds it (chordMatterShare,
// cloudlut_shading.glsl, with the table's chord_outer_third_share: evenly within each third of
// the span, the middle third densest for the metaball fall-off), and
// τ_c beyond. This ramp is written as its second difference in w (a delta of slope at each of
// the four ends of the thirds, split between the integer slices about it) and recovered exactly
// at the integer slices by a double prefix sum from the sun side (see sunVolumeRampAt).

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Optical depth of the ramp of one chord at slice coordinate w (dimensionless):
// τ_c·chordMatterShare((wFirst − w)/(wFirst − wFar), a), a the table's chord_outer_third_share.
CLOUDLUT_FN float sunVolumeRampAt(float tauChord, float wFirst, float wFar, float w, float outerThird) {
  float span = max(wFirst - wFar, 1e-6f);
  return tauChord * chordMatterShare((wFirst - w) / span, outerThird);
}

// Weight of the ramp's delta at wEdge carried by integer slice k (linear split between
// floor(wEdge) and floor(wEdge) + 1): the double prefix sum of these weights times the ramp's
// slope reproduces max(0, wEdge − k) exactly at every integer k.
CLOUDLUT_FN vec2 sunVolumeDeltaSplit(float wEdge) {
  float f = wEdge - floor(wEdge);
  return vec2(1.0f - f, f);
}
