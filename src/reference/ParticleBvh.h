#pragma once
// A bounding-volume hierarchy over the particles of a path-traced scene (reference/
// ScenePathTracer.h), so that a ray finds the particles it may cross without testing all N.
//
// Each particle i is the ellipsoid x = c_i + M_i·p, |p| ≤ 1. Its axis-aligned bounding box is
// exact: along world axis k the ellipsoid reaches c_i,k ± ‖row_k(M_i)‖ (the largest of
// e_k·M_i·p over the unit ball), in world units. The boxes are padded by 10⁻⁶ of the particle's
// largest half-extent plus 10⁻¹² of its centre's largest coordinate (world units), far above the
// rounding of the exact ellipsoid test, so the cull is conservative: every particle whose
// ellipsoid the exact test accepts is returned.
//
// The tree: binary, split at the median centroid along the longest axis of the centroid box,
// leaves of at most kLeafSize particles; build O(N log N), deterministic (no threads).
// candidates() returns the particles whose boxes meet the ray segment [0, tMax] (world units),
// sorted by index, so that a caller testing them in that order reproduces the brute-force loop
// over all particles bit for bit.
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace cloudlut::reference {

struct SceneParticle;

class ParticleBvh {
 public:
  static constexpr int kLeafSize = 4;

  explicit ParticleBvh(const std::vector<SceneParticle>& particles);

  // Indices (ascending) of the particles whose padded boxes meet origin + t·direction for
  // t ∈ [0, tMax]; `out` is cleared first. `direction` need not be normalised.
  void candidates(const glm::dvec3& origin, const glm::dvec3& direction, double tMax,
                  std::vector<std::uint32_t>& out) const;

  std::size_t nodeCount() const { return nodes_.size(); }

 private:
  struct Box {
    glm::dvec3 lo, hi;
  };
  struct Node {
    Box box;
    std::uint32_t first = 0, count = 0;  // leaf: particles order_[first, first + count)
    std::uint32_t left = 0, right = 0;   // inner (count == 0): child nodes
  };

  std::uint32_t build(std::uint32_t first, std::uint32_t count, const std::vector<glm::dvec3>& centroids);

  std::vector<Box> boxes_;            // per particle
  std::vector<std::uint32_t> order_;  // particle indices, grouped by leaf
  std::vector<Node> nodes_;           // nodes_[0] = root (when not empty)
};

// The exact world-space bounding box of particle p (half-extent ‖row_k(M)‖ along axis k, where
// M = toParticle⁻¹), unpadded; world units.
void particleBounds(const SceneParticle& p, glm::dvec3& lo, glm::dvec3& hi);

}  // namespace cloudlut::reference
