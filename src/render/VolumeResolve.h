#pragma once
// Volume-aware blending (seed §5.5, eqs. 10–17, generalised to any number of overlapping
// particles): the per-pixel fragment lists that the particle pass fills (a node pool and an r32ui
// image of list heads; shaders/volume_fragments.glsl) and their exact resolve: each pixel's
// segments are cut at every entry and exit, inside each piece the extinctions add and the colours
// combine weighted by extinction, and the pieces are composited front to back
// (shaders/volume_pieces.glsl). The segments are taken in depth order (a total order: ties by the
// nodes' other words), so the result does not depend on the order the fragments arrived in; the
// fragments that found no room in the pool (alpha-blended by the particle pass, in arrival order)
// are composited behind them.
//
// The particle pass lists the pixels whose list it starts, and the resolves visit only those.
// Six programs. The first counts each listed pixel's segments and composites the lists of one
// (shaders/volume_resolve_single.comp.glsl); it hands each longer list to the program for up to
// 4, 8, 16 or 32 segments (kSortedResolveSlots; at most RenderSettings::volumeShortList), or to
// the chunked one. Up to 32 they are sorted by a
// sorting network written out with constant indices (render/SortingNetwork.h,
// shaders/volume_resolve_sorted.comp.glsl), so their events stay in registers; the longer ones
// are sorted in chunks of kMaxSegmentsPerPixel in arrays, each chunk composited exactly and the
// chunks front to back (shaders/volume_resolve.comp.glsl). llvmpipe keeps a shader's dynamically
// indexed arrays in memory and pays for them in every invocation of the program, whether it
// touches them or not: one program over every pixel of the tile made the resolve take 150 of a
// single particle's 210 ms per frame at 1280×720.
//
// Tiles: the node pool of one shader storage block holds the lists of one screen tile at a time.
// The buffer is cut into bands (or, when one row does not fit, runs of pixels) of at most
// P = ⌊(B − 16) / (28 · F)⌋ pixels, B the pool budget in bytes (the smaller of the settings'
// volume pool budget and what StorageBudget allows: GL_MAX_SHADER_STORAGE_BLOCK_SIZE, half the
// machine's memory), F the fragments per pixel (the expected fragment load), 28 the bytes of a
// node; the particles are drawn once per tile, scissored to it, and the tile is resolved before
// the pool is emptied for the next. Every pixel sees its whole list, so the tiled image is the
// untiled one.
//
// That plan expects F fragments on every pixel. Where they crowd (a cloudscape's horizon) its
// tiles overflow, and each overflowed tile's first draw is shaded for nothing. planBands replaces
// it by bands of whole rows cut from the fragments counted per row beforehand (ParticlePass::
// countFragments runs the particle shader's own ray test), each band filling the whole budget:
// none overflows unless one row alone holds more fragments than the pool, which run() splits as
// any overflowed tile (docs/BENCHMARKS.md, "Screen tiles of a cloudscape"). run() can also count
// late, at the expected plan's first overflow: the rows not drawn yet are still clear in the colour
// texture, so the count adds into them there, and only the overflowed tile is drawn twice.
//
// A pixel with L segments makes about L²/kMaxSegmentsPerPixel loop passes in the resolve. llvmpipe
// ends every loop of a shader invocation once its loops have made 65535 passes in all, which
// hundreds of segments on one pixel reach (600 stacked particles do not, 1000 do): such a pixel
// loses its farther segments. The resolve tells these pixels (a last loop of two passes makes
// only one) and counts them apart (Counts::cutPixels, RenderStats::resolveCutPixels; the count
// takes in every pixel of an invocation that ran out, so it may exceed the pixels harmed);
// `render` warns. A GL without the limit never cuts.
//
// The chunked resolve stops once the chunks composited so far let through less than
// kOpaqueTransmittance: what lies behind adds at most that share of its radiance, below a float's
// rounding of the pixel. In a cloudscape nearly every list longer than a chunk is that opaque
// after its first chunk, and its other walks of the list were most of the resolve's time
// (docs/BENCHMARKS.md, "The chunked resolve stops at an opaque chunk").
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"

namespace cloudlut::render {

// The chunked resolve's stop: a pixel's transmittance in front of the chunks not yet taken
// (dimensionless). Its farther segments then change no float of the pixel that matters: the
// radiance they would add is at most this share of theirs.
inline constexpr float kOpaqueTransmittance = 1e-7f;

// Words (4 bytes) per fragment node: entry, exit, τ, radiance r, g, b, next.
inline constexpr int kFragmentNodeWords = 7;

// The share of the pool's nodes that planned bands leave free (VolumeResolve::planBands): a
// margin for a count that misses a fragment the pass stores (the two programs' rounding).
inline constexpr double kBandHeadroom = 0.01;

// Bytes the fragment pool needs for a width × height particle buffer: its four counters and
// fragmentsPerPixel nodes per pixel.
long double volumePoolBytes(int width, int height, int fragmentsPerPixel);

// The default budget of the node pool (bytes), before StorageBudget's limit.
inline constexpr long double kDefaultVolumePoolBytes = 128.0L * 1048576.0L;

// The tiles of a width × height buffer: columns × rows tiles of tileWidth × tileHeight pixels
// (the last column and row clipped to the buffer), each one pool of poolBytes bytes.
struct VolumeTiling {
  int width = 0, height = 0;
  int tileWidth = 0, tileHeight = 0;
  int columns = 0, rows = 0;
  std::size_t poolBytes = 0;
  int count() const { return columns * rows; }
};

// The tiling of the header's rule for a pool budget of `budgetBytes`; UsageError when not even
// one pixel's nodes fit.
VolumeTiling planVolumeTiles(int width, int height, int fragmentsPerPixel, long double budgetBytes);

// Bands of whole rows [first, end) from the fragments counted in each row (rowFragments, bottom
// row first): each band as many rows as keep its fragments within `capacity` nodes and its
// pixels within `maxPixels` (the pixel lists' room), taken greedily from the bottom, which makes
// the fewest bands a partition into runs of rows can have. A row over `capacity` on its own is a
// band of one row (drawn, found over, split by run()).
struct VolumeBand {
  int first = 0, end = 0;
};
std::vector<VolumeBand> planVolumeBands(const std::vector<double>& rowFragments, int width, double capacity,
                                        std::size_t maxPixels);

class VolumeResolve {
 public:
  VolumeResolve(const GlFunctions& gl, const StorageBudget& budget);
  ~VolumeResolve();
  VolumeResolve(const VolumeResolve&) = delete;
  VolumeResolve& operator=(const VolumeResolve&) = delete;

  // The #defines of the programs that write or read the lists (FRAGMENT_NODE_WORDS,
  // PIXEL_LIST_REGIONS).
  static std::string fragmentDefines();

  // Plans the tiles of a width × height buffer for a pool budget of `budgetBytes` (capped by the
  // storage budget; 0: kDefaultVolumePoolBytes), sizes the pool for one tile, empties the lists.
  // Lists of up to shortList segments (0 … kShortListCapacity) go to the sorted resolves.
  VolumeTiling prepare(int width, int height, int fragmentsPerPixel, long double budgetBytes, int shortList);
  // Replans the prepared buffer's tiles as bands of rows from its fragments counted per pixel
  // (the red channel of `countTexture`, RGBA32F of the prepared size; ParticlePass::
  // countFragments): planVolumeBands with the pool at the whole budget, less kBandHeadroom of
  // its nodes. The expected load's plan overflows where the fragments crowd (a cloudscape's
  // horizon), and an overflowed tile's first draw is shaded for nothing.
  void planBands(GLuint countTexture);
  // For each tile of the prepared tiling: empties the pool, binds it and the heads for the
  // particle pass (pool at binding 2, pixel lists at binding 4, heads at image unit 0), scissors
  // to the tile, calls drawTile, then composites the tile's lists into the colour texture
  // (RGBA32F, as prepared): in, the fragments that found no room (radiance, transmittance); out,
  // the result. A tile whose fragments overflow the pool is undone and drawn again as two halves
  // (down to one pixel), so the plan adapts to the fragment load and stays exact. With countTile
  // (a pass that adds each fragment's 1 into the colour texture's red channel under the current
  // scissor; ParticlePass::countFragments), the expected plan's first overflowed band is instead
  // undone and the rows from it up are counted and planned as planBands plans (Counts::
  // countedPlan): one tile shaded for nothing, where the halves could be many. counts() then
  // holds the sums over the tiles.
  void run(GLuint colourTexture, const std::function<void()>& drawTile, const std::function<void()>& countTile = {});
  // Binds a small pool, small pixel lists and a 1×1 head image, for a particle pass that stores no
  // fragments.
  void bindUnused();

  struct Counts {
    std::size_t fragments = 0;        // produced
    std::size_t overflow = 0;         // alpha-blended for want of pool room
    std::size_t truncatedPixels = 0;  // pixels whose resolve took more than one chunk (not opaque after it)
    std::size_t midLists = 0;         // pixels with more than min(8, short list) segments (stage 2 on)
    std::size_t longLists = 0;        // pixels with more than the short list's segments (chunked)
    std::size_t cutPixels = 0;        // pixels whose resolve the GL cut short (loop budget; header)
    std::size_t tiles = 0;            // tiles resolved (the plan's, and the parts of split ones)
    std::size_t redrawnTiles = 0;     // tiles drawn, found over the pool's room and split in two
    std::size_t countedFragments = 0;  // fragments counted for the bands (the rows they cover)
    bool countedPlan = false;          // the tiles (all, or from the first overflow up) are counted bands
    bool expectedPlanOverflows = false;  // counted: prepare's tiles would have overflowed (or did)
  };
  Counts counts() const { return counts_; }
  // prepare's tiling (the expected load's plan), which planBands does not change.
  const VolumeTiling& tiling() const { return tiling_; }
  // Fragments one tile of prepare's plan holds (its pool's nodes): a frame with no more fragments
  // than that cannot overflow it.
  std::size_t expectedTileNodes() const;
  // Bytes of the node pool run() fills, one tile's: the tiling's, or planBands' whole budget.
  std::size_t poolBytes() const { return poolBytes_; }
  // Seconds the resolves of the last run took (glFinish each).
  double resolveSeconds() const { return resolveSeconds_; }

 private:
  const GlFunctions& gl_;
  const StorageBudget& budget_;
  // Linked when a frame first needs them: llvmpipe compiles the straight-line network of 32
  // segments (543 compare-exchanges) in seconds, once per machine with its shader cache.
  std::array<GlProgram, kSortedResolveSlots.size()> sortedPrograms_;
  GlProgram singleProgram_;  // the first resolve: lists of one segment, the others sorted out
  GlProgram longProgram_;
  StorageBuffer pool_;
  StorageBuffer cut_;        // the resolves' count of pixels the GL cut short (binding 3)
  StorageBuffer pixelLists_;  // the pixels with a list, by region (binding 4, volume_fragments.glsl)
  StorageBuffer rowCounts_;   // planBands' fragments per row (binding 5, volume_row_counts.comp.glsl)
  GlProgram rowCountsProgram_;  // linked on first use
  int shortList_ = kShortListCapacity;
  GLuint heads_ = 0, unusedHeads_ = 0;
  BufferTexels nodeWords_;  // over pool_, R32UI, for the resolves (volume_fragments.glsl); caps the pool
  int width_ = 0, height_ = 0;
  VolumeTiling tiling_;
  std::size_t poolBytes_ = 0;  // the plan's pool (poolBytes())
  struct Rect {
    int x0, y0, x1, y1;
  };
  std::vector<Rect> tiles_;  // the tiles run() draws, in order: the tiling's, or planBands'
  std::size_t tilePixels_ = 0;  // the most pixels any tile of the plan has
  long double budgetBytes_ = 0;  // the pool's budget (prepare)
  Counts counts_;
  double resolveSeconds_ = 0;

  const GlProgram& sortedProgram(std::size_t stage);  // linked on first use
  // The fragments counted in each row of countTexture's red channel (bottom row first).
  std::vector<double> countedRows(GLuint countTexture);
  // tiles_ (and the pool, the pixel lists' size): bands of the rows from firstRow up.
  void planBandsFrom(const std::vector<double>& rows, int firstRow);
  void resolveTile(GLuint colourTexture);
};

}  // namespace cloudlut::render
