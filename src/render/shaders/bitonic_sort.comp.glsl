// bitonic_sort.comp.glsl — one compare-exchange pass (k, j) of a bitonic sort of the
// (distance, particle) keys, largest distance first (back to front). The key buffer is padded
// to a power of two with distance -1, which sorts last. GROUP_SIZE (threads per work group) is
// defined by render/CloudscapeGeneration.cpp, which dispatches it.

layout(local_size_x = GROUP_SIZE) in;

uniform uint uK;
uniform uint uJ;
uniform uint uCount;  // power of two

layout(std430, binding = 1) buffer SortKeys {
  uvec2 sortKeys[];
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  uint l = i ^ uJ;
  if (l <= i) return;
  uvec2 a = sortKeys[i];
  uvec2 b = sortKeys[l];
  float da = uintBitsToFloat(a.x);
  float db = uintBitsToFloat(b.x);
  bool descending = (i & uK) == 0u;
  // Ties broken by index so that the order is deterministic.
  bool aBefore = da > db || (da == db && a.y < b.y);
  if (descending != aBefore) {
    sortKeys[i] = b;
    sortKeys[l] = a;
  }
}
