// occlusion.comp.glsl — light-space occlusion (seed §5.3). Preceded by particle_common.glsl and
// the defines of render/LightOcclusion.cpp, which sizes the buffers and dispatches the stages:
// GROUP_SIZE (threads per work group) and STAGE; the grid's tiles per side are uTiles (from the
// particle count, render/LightOcclusion.h):
//   STAGE 0: bounds of the particles seen from the sun (atomic min/max in light space u, v);
//   STAGE 1: tiling: each particle, extended by half a tile (conservative), is pushed onto the
//            linked list of every tile it covers (atomic counter + atomic exchange of heads);
//   STAGE 2: per particle, the list of the tile holding its centre: the ray from its centre toward
//            the sun against every other particle, optical depth of the chord (homogeneous
//            ellipsoid, ρ·σ per unit-sphere length) scaled by ξ: sunlight = exp(-ξ Σ τ);
//   STAGE 3: density-weighted smoothing of the sunlight over the particles of the same tile within
//            twice the particle's radius (light diffusing through the cloud body).

layout(local_size_x = GROUP_SIZE) in;

const uint NIL = 0xffffffffu;

uniform int uTiles;     // tiles per side of the light-space grid
#define TILES uTiles
uniform uint uCount;
uniform vec3 uSun;      // toward the sun
uniform vec3 uLightU;   // light-space axes, perpendicular to uSun
uniform vec3 uLightV;
uniform float uSigma;   // optical radius of a unit-density particle (beta * R)
uniform float uXi;      // extinction scale for occlusion (seed: 0.05)
uniform int uSmooth;

layout(std430, binding = 3) buffer Tiles {
  ivec4 bounds;         // ordered-int min u, min v, max u, max v
  uint nodeCount;
  uint nodeCapacity;
  uint nodeOverflow;
  uint pad;
  uint heads[];         // uTiles² list heads
};

layout(std430, binding = 7) buffer TileNodes {
  uvec2 nodes[];        // (particle, next)
};

layout(std430, binding = 4) buffer RawSunlight {
  float rawSunlight[];
};

int orderedInt(float f) {
  int i = floatBitsToInt(f);
  return i >= 0 ? i : i ^ 0x7fffffff;
}
float orderedFloat(int i) { return intBitsToFloat(i >= 0 ? i : i ^ 0x7fffffff); }

float reach(GpuParticle p) {
  return max(length(p.toWorld[0].xyz), max(length(p.toWorld[1].xyz), length(p.toWorld[2].xyz)));
}

vec4 tileFrame() {  // (min u, min v, tile width u, tile width v)
  vec2 lo = vec2(orderedFloat(bounds.x), orderedFloat(bounds.y));
  vec2 hi = vec2(orderedFloat(bounds.z), orderedFloat(bounds.w));
  vec2 size = max((hi - lo) / float(TILES), vec2(1e-6f * max(max(abs(lo.x), abs(hi.x)), 1.0f)));
  return vec4(lo, size);
}

ivec2 tileOf(vec2 uv, vec4 frame) {
  return clamp(ivec2(floor((uv - frame.xy) / frame.zw)), ivec2(0), ivec2(TILES - 1));
}

// First node of the list of the tile holding the light-space point uv.
uint tileListOf(vec2 uv) {
  ivec2 t = tileOf(uv, tileFrame());
  return heads[t.y * TILES + t.x];
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  GpuParticle p = particles[i];
  vec3 c = p.centerDensity.xyz;
  vec2 uv = vec2(dot(c, uLightU), dot(c, uLightV));
#if STAGE == 0
  float r = reach(p);
  atomicMin(bounds.x, orderedInt(uv.x - r));
  atomicMin(bounds.y, orderedInt(uv.y - r));
  atomicMax(bounds.z, orderedInt(uv.x + r));
  atomicMax(bounds.w, orderedInt(uv.y + r));
#elif STAGE == 1
  vec4 frame = tileFrame();
  float r = reach(p);
  ivec2 lo = tileOf(uv - vec2(r) - 0.5f * frame.zw, frame);
  ivec2 hi = tileOf(uv + vec2(r) + 0.5f * frame.zw, frame);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) {
      uint node = atomicAdd(nodeCount, 1u);
      if (node >= nodeCapacity) {
        atomicAdd(nodeOverflow, 1u);
        return;
      }
      uint next = atomicExchange(heads[y * TILES + x], node);
      nodes[node] = uvec2(i, next);
    }
#elif STAGE == 2
  float tau = 0.0f;
  uint node = tileListOf(uv);
  for (int guard = 0; node != NIL && guard < 1000000; ++guard) {
    uvec2 n = nodes[node];
    node = n.y;
    if (n.x == i) continue;
    GpuParticle q = particles[n.x];
    mat3 toParticle = mat3(q.toParticle[0].xyz, q.toParticle[1].xyz, q.toParticle[2].xyz);
    vec3 o = toParticle * (c - q.centerDensity.xyz);
    vec3 d = toParticle * uSun;
    float a = dot(d, d);
    float b = dot(o, d);
    float cc = dot(o, o) - 1.0f;
    float disc = b * b - a * cc;
    if (disc <= 0.0f) continue;
    float s = sqrt(disc);
    float t0 = max((-b - s) / a, 0.0f);
    float t1 = (-b + s) / a;
    if (t1 <= t0) continue;
    tau += q.centerDensity.w * uSigma * (t1 - t0) * sqrt(a);
  }
  rawSunlight[i] = exp(-uXi * tau);
#else
  float own = rawSunlight[i];
  float result = own;
  if (uSmooth != 0) {
    float radius = 2.0f * reach(p);
    float wsum = p.centerDensity.w;
    float sum = wsum * own;
    uint node = tileListOf(uv);
    for (int guard = 0; node != NIL && guard < 1000000; ++guard) {
      uvec2 n = nodes[node];
      node = n.y;
      if (n.x == i) continue;
      GpuParticle q = particles[n.x];
      float dist = length(q.centerDensity.xyz - c);
      if (dist >= radius) continue;
      float w = q.centerDensity.w * (1.0f - dist / radius);
      sum += w * rawSunlight[n.x];
      wsum += w;
    }
    result = wsum > 0.0f ? sum / wsum : own;
  }
  particles[i].toParticle[2].w = result;
#endif
}
