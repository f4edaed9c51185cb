#include "reference/ParticleBvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include "reference/ScenePathTracer.h"

namespace cloudlut::reference {

void particleBounds(const SceneParticle& p, glm::dvec3& lo, glm::dvec3& hi) {
  const glm::dmat3 m = glm::inverse(p.toParticle);  // M: unit sphere → world offset
  glm::dvec3 h;
  for (int k = 0; k < 3; ++k) h[k] = std::sqrt(m[0][k] * m[0][k] + m[1][k] * m[1][k] + m[2][k] * m[2][k]);
  lo = p.center - h;
  hi = p.center + h;
}

ParticleBvh::ParticleBvh(const std::vector<SceneParticle>& particles) {
  const std::size_t n = particles.size();
  boxes_.resize(n);
  order_.resize(n);
  std::vector<glm::dvec3> centroids(n);
  for (std::size_t i = 0; i < n; ++i) {
    glm::dvec3 lo, hi;
    particleBounds(particles[i], lo, hi);
    const glm::dvec3 h = 0.5 * (hi - lo);
    // Padding: relative 1e-6 of the largest half-extent (plus the rounding of the centre).
    const double pad = 1e-6 * std::max({h.x, h.y, h.z}) +
                       1e-12 * std::max({std::abs(particles[i].center.x), std::abs(particles[i].center.y),
                                         std::abs(particles[i].center.z)});
    boxes_[i] = {lo - pad, hi + pad};
    centroids[i] = particles[i].center;
    order_[i] = static_cast<std::uint32_t>(i);
  }
  if (n > 0) {
    nodes_.reserve(2 * n / kLeafSize + 2);
    build(0, static_cast<std::uint32_t>(n), centroids);
  }
}

std::uint32_t ParticleBvh::build(std::uint32_t first, std::uint32_t count, const std::vector<glm::dvec3>& centroids) {
  const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Box box{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
  glm::dvec3 cLo = box.lo, cHi = box.hi;
  for (std::uint32_t k = first; k < first + count; ++k) {
    box.lo = glm::min(box.lo, boxes_[order_[k]].lo);
    box.hi = glm::max(box.hi, boxes_[order_[k]].hi);
    cLo = glm::min(cLo, centroids[order_[k]]);
    cHi = glm::max(cHi, centroids[order_[k]]);
  }
  nodes_[index].box = box;
  if (count <= static_cast<std::uint32_t>(kLeafSize)) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const glm::dvec3 extent = cHi - cLo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t half = count / 2;
  // Median by centroid along `axis`, ties broken by index so that the tree is deterministic.
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return centroids[a][axis] < centroids[b][axis] ||
                            (centroids[a][axis] == centroids[b][axis] && a < b);
                   });
  const std::uint32_t left = build(first, half, centroids);
  const std::uint32_t right = build(first + half, count - half, centroids);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

namespace {

// A ray segment prepared for slab tests: origin, 1/direction per axis, and which axes the ray
// does not move along.
struct SlabRay {
  glm::dvec3 o, inv;
  bool still[3];
  double tMax;
};

// Does origin + t·direction, t ∈ [0, tMax], meet the closed box? Slab test; an axis the ray
// does not move along only checks that the origin lies within the slab.
bool segmentMeetsBox(const glm::dvec3& lo, const glm::dvec3& hi, const SlabRay& r) {
  double t0 = 0.0, t1 = r.tMax;
  for (int k = 0; k < 3; ++k) {
    if (r.still[k]) {
      if (r.o[k] < lo[k] || r.o[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - r.o[k]) * r.inv[k], tb = (hi[k] - r.o[k]) * r.inv[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

void ParticleBvh::candidates(const glm::dvec3& origin, const glm::dvec3& direction, double tMax,
                             std::vector<std::uint32_t>& out) const {
  out.clear();
  if (nodes_.empty()) return;
  SlabRay ray{origin, glm::dvec3(0.0), {false, false, false}, tMax};
  for (int k = 0; k < 3; ++k) {
    ray.still[k] = direction[k] == 0.0;
    ray.inv[k] = ray.still[k] ? 0.0 : 1.0 / direction[k];
  }
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!segmentMeetsBox(node.box.lo, node.box.hi, ray)) continue;
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        const Box& b = boxes_[order_[k]];
        if (segmentMeetsBox(b.lo, b.hi, ray)) out.push_back(order_[k]);
      }
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  std::sort(out.begin(), out.end());
}

}  // namespace cloudlut::reference
