// particle.vert.glsl — rasterises a proxy of each particle's ellipsoid (seed §5.4): one instance
// per particle, in the back-to-front order of the particle buffer or of the sorted keys (front
// to back, reversed, under hidden-fragment culling), 36 vertices each. The fragment shader
// intersects the view ray with the ellipsoid itself, so a proxy only has to cover its outline,
// once per pixel; the smaller it is, the fewer fragments llvmpipe rasterises and discards.
//   Seen from afar (the eye at least kPolygonClearance bounding radii from the centre, beyond the
//   near plane): a polygon of kPolygonSides sides circumscribing the ellipsoid's silhouette,
//   1.06 times the outline's area (the box's back faces cover about 1.6 times as much). In the
//   particle's frame (unit sphere, eye at e, d = |e|) the tangent cone from the eye touches the
//   sphere along the circle of centre e/d² and radius sqrt(1 − 1/d²) in the plane normal to e;
//   every ray that meets the sphere crosses that plane inside the circle, so a polygon around the
//   circle in the same plane covers the outline. The map to world space is affine, which keeps
//   planes, tangency and incidence: the same holds for the ellipsoid.
//   Close by, or with the eye inside: the bounding box, wound counter-clockwise seen from outside
//   (the renderer culls front faces, so each covered pixel still gets exactly one fragment).
// The polygon is wound clockwise seen from the eye, a back face like the box's.

uniform mat4 uViewProjection;
uniform vec3 uEye;        // world
uniform float uNearPlane; // world distance of the near clipping plane
uniform int uOutlinePolygons;  // 1: the polygon where it applies, 0: always the box
uniform int uUseOrder;  // 1: draw in the order of the sorted keys (GPU bitonic sort), 0: buffer order
uniform int uFirstInstance;    // instance 0 draws this one (a batch of the pass)
uniform int uInstanceCount;    // > 0: the pass draws this many, last first (front to back)
uniform float uHiddenDepthScale;  // > 0: the proxy's depth (below), 1 / far plane (world units⁻¹)

layout(std430, binding = 1) readonly buffer SortKeys {
  uvec2 sortKeys[];  // (distance bits, particle index), back to front
};

// particle_varyings.glsl's
out vec3 vWorld;
flat out int vParticle;
flat out vec4 vCenterDensity;
flat out vec4 vToParticle[3];

const vec3 kBoxCorners[24] = vec3[24](
  vec3( 1, -1, -1), vec3( 1,  1, -1), vec3( 1,  1,  1), vec3( 1, -1,  1),   // +x
  vec3(-1, -1, -1), vec3(-1, -1,  1), vec3(-1,  1,  1), vec3(-1,  1, -1),   // -x
  vec3(-1,  1, -1), vec3(-1,  1,  1), vec3( 1,  1,  1), vec3( 1,  1, -1),   // +y
  vec3(-1, -1, -1), vec3( 1, -1, -1), vec3( 1, -1,  1), vec3(-1, -1,  1),   // -y
  vec3(-1, -1,  1), vec3( 1, -1,  1), vec3( 1,  1,  1), vec3(-1,  1,  1),   // +z
  vec3(-1, -1, -1), vec3(-1,  1, -1), vec3( 1,  1, -1), vec3( 1, -1, -1));  // -z
const int kQuadCorner[6] = int[6](0, 1, 2, 0, 2, 3);

const int kPolygonSides = 8;             // a fan of kPolygonSides − 2 triangles; the rest degenerate
const float kPolygonClearance = 1.25;    // eye distance from the centre, in bounding radii, + near plane
const float kPolygonMargin = 1.005;      // the polygon's inradius over the circle's (rounding)
const float kPi = 3.14159265358979;

// Corner `k` (0 … kPolygonSides − 1) of the polygon around the silhouette circle, in the
// particle's frame, for the eye at e (|e| > 1); clockwise seen from the eye as k grows.
vec3 silhouettePolygonCorner(vec3 e, int k) {
  float d2 = dot(e, e);
  vec3 n = e * inversesqrt(d2);
  vec3 u = normalize(abs(n.x) < 0.9 ? cross(n, vec3(1, 0, 0)) : cross(n, vec3(0, 1, 0)));
  vec3 w = cross(n, u);  // (u, w, n) right-handed: angle from u toward w is counter-clockwise seen from +n
  float circumradius = sqrt(max(1.0 - 1.0 / d2, 0.0)) * kPolygonMargin / cos(kPi / float(kPolygonSides));
  float angle = -2.0 * kPi * float(k) / float(kPolygonSides);
  return e / d2 + circumradius * (cos(angle) * u + sin(angle) * w);
}

void main() {
  int instance = gl_InstanceID + uFirstInstance;
  if (uInstanceCount > 0) instance = uInstanceCount - 1 - instance;
  int index = uUseOrder != 0 ? int(sortKeys[instance].y) : instance;
  GpuParticle p = particles[index];
  mat3 toWorld = mat3(p.toWorld[0].xyz, p.toWorld[1].xyz, p.toWorld[2].xyz);
  vec3 fromCentre = uEye - p.centerDensity.xyz;
  float boundingRadius = p.toParticle[1].w;
  vec3 corner;
  if (uOutlinePolygons != 0 && length(fromCentre) > kPolygonClearance * boundingRadius + uNearPlane) {
    mat3 toParticle = particleToUnitSphere(p);
    int triangle = gl_VertexID / 3, vertex = gl_VertexID % 3;
    // fan (0, t + 1, t + 2) for t < kPolygonSides − 2; the later triangles collapse onto corner 0
    int k = triangle < kPolygonSides - 2 && vertex > 0 ? triangle + vertex : 0;
    corner = silhouettePolygonCorner(toParticle * fromCentre, k);
  } else {
    corner = kBoxCorners[(gl_VertexID / 6) * 4 + kQuadCorner[gl_VertexID % 6]];
  }
  vWorld = p.centerDensity.xyz + toWorld * corner;
  vParticle = index;
  vCenterDensity = p.centerDensity;
  vToParticle = p.toParticle;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
  // Hidden-fragment culling (render/HiddenFragments.h): the whole proxy at the depth of the
  // particle's nearest point, |c − eye| − bounding radius, times uHiddenDepthScale, so that the
  // early depth test drops it where the depth buffer holds a nearer hidden distance.
  if (uHiddenDepthScale > 0.0) {
    float depth = clamp(max(length(fromCentre) - boundingRadius, 0.0) * uHiddenDepthScale, 0.0, 1.0);
    gl_Position.z = (2.0 * depth - 1.0) * gl_Position.w;
  }
}
