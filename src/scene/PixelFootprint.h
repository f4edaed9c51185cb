#pragma once
// Upper bounds on the pixels whose centre rays meet a particle: the fragments a particle pass that
// shades one fragment per pixel of each particle's ray-traced outline can store. Exact bounds,
// loose by the bounding sphere's screen rectangle (4/π of a sphere's disc and a pixel's rim), for planning storage before a frame is drawn.
#include <cstddef>
#include <vector>

#include "scene/Scene.h"

namespace cloudlut::scene {

// Pixels of `frame`'s image inside the screen rectangle of p's bounding sphere (radius its
// largest semi-axis; the rectangle its projection touches), one pixel wider on each side; the
// whole image when that sphere reaches the plane through the eye (the eye may be inside), none
// when it lies wholly behind that plane.
std::size_t pixelFootprintBound(const Particle& p, const CameraFrame& frame);

// The sum over `particles` (fragments, at most one per particle and pixel).
std::size_t pixelFootprintBound(const std::vector<Particle>& particles, const CameraFrame& frame);

}  // namespace cloudlut::scene
