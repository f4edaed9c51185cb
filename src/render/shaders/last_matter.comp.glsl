// last_matter.comp.glsl — the optical-depth texture the renderer shades with: per node of the
// file's table, its two channels and a third, the last matter of the node's chord
// (core/LastMatter.h computes the same on the CPU, and the tests hold the two together):
//   last = max(1 − first matter of the reversed chord (E, −v), first matter of (S, v)),
// E = S + L·v the chord's exit (dimensionless fractions of the chord). One invocation per node;
// preceded by cloudlut_geometry.glsl and cloudlut_sampling.glsl (render/LastMatterTexture.cpp).

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

uniform sampler3D uOpticalDepth;  // the file's table: mean density, first matter (folded 4D, cloudlutSample4D)
uniform vec4 uOpticalDepthDims;   // (N0, N1, N2, N3)
uniform vec4 uAxisMin;            // the node values of axes 0..3 (φS, θS, φv, θv; radians) run
uniform vec4 uAxisMax;            // linearly from uAxisMin at node 0 to uAxisMax at node N − 1
layout(rgba32f, binding = 0) uniform writeonly image3D uOut;

void main() {
  ivec3 t = ivec3(gl_GlobalInvocationID);
  ivec4 n = ivec4(uOpticalDepthDims);
  if (t.x >= n.x || t.y >= n.y || t.z >= n.z * n.w) return;
  ivec4 i = ivec4(t.x, t.y, t.z % n.z, t.z / n.z);
  vec4 a = uAxisMin + (uAxisMax - uAxisMin) * vec4(i) / vec4(max(n - 1, ivec4(1)));
  vec3 S = sphericalPoint(a.x, a.y);
  vec3 v = opticalDepthNodeDirection(a.x, a.y, a.z, a.w);
  vec2 od = texelFetch(uOpticalDepth, t, 0).xy;
  vec3 E = normalize(S + chordLength(S, v) * v);
  float firstBack = clamp(cloudlutSample4D(uOpticalDepth, opticalDepthAxes(E, -v), uOpticalDepthDims).y, 0.0, 1.0);
  imageStore(uOut, t, vec4(od, max(1.0 - firstBack, clamp(od.y, 0.0, 1.0)), 0.0));
}
