#include "core/LastMatter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/Glsl.h"

namespace cloudlut {

namespace {

// Channel 1 of the table at the chord (S, v), clamped to [0, 1].
float firstMatterAt(const Table4D& opticalDepth, const glm::vec3& S, const glm::vec3& v) {
  const glm::vec4 x = glsl::opticalDepthAxes(S, v);
  float values[4] = {0, 0, 0, 0};
  opticalDepth.sample({x.x, x.y, x.z, x.w}, values);
  return std::clamp(values[1], 0.0f, 1.0f);
}

// The last matter given the chord's own first matter.
float lastMatterFrom(const Table4D& opticalDepth, const glm::vec3& S, const glm::vec3& v, float firstMatter) {
  const glm::vec3 exit = glm::normalize(S + glsl::chordLength(S, v) * v);
  return std::max(1.0f - firstMatterAt(opticalDepth, exit, -v), firstMatter);
}

}  // namespace

float lookupLastMatter(const Table4D& opticalDepth, const glm::vec3& S, const glm::vec3& v) {
  if (opticalDepth.channelCount() < 2) return 1.0f;  // no first matter stored: the matter starts at S, ends at E
  return lastMatterFrom(opticalDepth, S, v, firstMatterAt(opticalDepth, S, v));
}

Table4D withLastMatterChannel(const Table4D& opticalDepth) {
  const auto& axes = opticalDepth.axes();
  const bool hasFirstMatter = opticalDepth.channelCount() > 1;
  std::vector<Channel> channels(opticalDepth.channels().begin(),
                                opticalDepth.channels().begin() + (hasFirstMatter ? 2 : 1));
  if (!hasFirstMatter) channels.push_back({"first_matter", "absent from the file: 0"});
  channels.push_back({"last_matter", "distance along the chord to the last density >= threshold, divided by the "
                                     "chord length (derived: 1 - first_matter of the reversed chord)"});
  Table4D out(opticalDepth.name(), axes, channels);
  out.parameters() = opticalDepth.parameters();
  const int n0 = axes[0].size, n1 = axes[1].size, n2 = axes[2].size, n3 = axes[3].size;
  const auto angle = [&axes](int axis, int i) { return static_cast<float>(axes[axis].value(i)); };
  tbb::parallel_for(tbb::blocked_range<int>(0, n2 * n3), [&](const tbb::blocked_range<int>& r) {
    for (int slice = r.begin(); slice != r.end(); ++slice) {
      const int i2 = slice % n2, i3 = slice / n2;
      for (int i1 = 0; i1 < n1; ++i1)
        for (int i0 = 0; i0 < n0; ++i0) {
          const std::size_t node = out.index(i0, i1, i2, i3);
          out.at(node, 0) = opticalDepth.at(node, 0);
          if (!hasFirstMatter) {  // the matter starts at the entry and ends at the exit
            out.at(node, 1) = 0.0f;
            out.at(node, 2) = 1.0f;
            continue;
          }
          // the node's chord as the baker laid it out (seed §4.1); at a node the table's own
          // first matter is the interpolated one
          const float phiS = angle(0, i0), thetaS = angle(1, i1);
          const glm::vec3 v = glsl::opticalDepthNodeDirection(phiS, thetaS, angle(2, i2), angle(3, i3));
          const float first = std::clamp(opticalDepth.at(node, 1), 0.0f, 1.0f);
          out.at(node, 1) = opticalDepth.at(node, 1);
          out.at(node, 2) = lastMatterFrom(opticalDepth, glsl::sphericalPoint(phiS, thetaS), v, first);
        }
    }
  });
  return out;
}

}  // namespace cloudlut
