#include "render/VolumeResolve.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/Errors.h"
#include "render/ShaderSources.h"
#include "render/SortingNetwork.h"
#include "render/Stopwatch.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kPoolBinding = 2, kCutBinding = 3, kPixelListsBinding = 4, kRowCountsBinding = 5;
constexpr unsigned kResolveGroup = 64;  // the resolves' local_size_x
// PixelLists (volume_fragments.glsl): a count per region and the capacity; then the regions of
// capacity pixel words: the listed pixels, one per sorted resolve, and the chunked resolve's.
constexpr std::size_t kPixelListRegions = kSortedResolveSlots.size() + 2;
constexpr std::size_t kPixelListHeaderWords = kPixelListRegions + 1;
constexpr GLuint kHeadsUnit = 0, kColourUnit = 1;  // image units
constexpr int kNodeWordsTextureUnit = 0;  // uFragmentNodeWords, every resolve's only sampler (its default unit)
// The pool (volume_fragments.glsl, block Fragments): count, capacity, overflow, truncated pixels.
constexpr std::size_t kCounterWords = 4;
constexpr std::size_t kNodeBytes = 4 * static_cast<std::size_t>(kFragmentNodeWords);
constexpr GLuint kListEnd = 0xffffffffu;

// The #defines of the sorted resolve's stage `stage` (shaders/volume_resolve_sorted.comp.glsl): its
// slots, sorting network and sweep written out with constant indices.
std::string sortedResolveDefines(std::size_t stage) {
  const int slots = kSortedResolveSlots[stage];
  std::string load, sweep;
  for (int k = 0; k < slots; ++k) load += "LOAD_SLOT(" + std::to_string(k) + ") ";
  for (int k = 0; k < 2 * slots; ++k) sweep += "SWEEP(" + std::to_string(k) + ") ";
  return glslDefine("STAGE", static_cast<int>(stage)) +
         glslDefine("STAGES", static_cast<int>(kSortedResolveSlots.size())) + glslDefine("SLOTS", slots) +
         glslDefine("SORTED_MAX", kShortListCapacity) + "#define LOAD_SLOTS " + load + "\n#define SORT_EVENTS " +
         networkGlsl(oddEvenMergeSortNetwork(2 * slots)) + "\n#define SWEEP_EVENTS " + sweep + "\n";
}

// Stage r sorts 4·2^r segments (the shader finds a list's stage from its length so).
constexpr bool stagesDouble() {
  for (std::size_t r = 0; r < kSortedResolveSlots.size(); ++r)
    if (kSortedResolveSlots[r] != (4 << r)) return false;
  return kSortedResolveSlots.back() == kShortListCapacity;
}
static_assert(stagesDouble(), "the sorted resolve's stages hold 4, 8, 16, … segments");

}  // namespace

long double volumePoolBytes(int width, int height, int fragmentsPerPixel) {
  return 4.0L * kCounterWords + static_cast<long double>(kNodeBytes) * static_cast<long double>(width) *
                                    static_cast<long double>(height) * static_cast<long double>(fragmentsPerPixel);
}

VolumeTiling planVolumeTiles(int width, int height, int fragmentsPerPixel, long double budgetBytes) {
  const long double perPixel = static_cast<long double>(kNodeBytes) * static_cast<long double>(fragmentsPerPixel);
  const long double fit = std::floor((budgetBytes - 4.0L * kCounterWords) / perPixel);
  if (!(fit >= 1.0L))
    throw UsageError("volume blending: a node pool of " + std::to_string(static_cast<double>(budgetBytes / 1048576.0L)) +
                     " MiB holds not even one pixel's " + std::to_string(fragmentsPerPixel) +
                     " fragments (--volume-pool-mib, --fragments-per-pixel)");
  auto divideUp = [](long double a, long double b) { return static_cast<int>(std::ceil(a / b)); };
  VolumeTiling t;
  t.width = width;
  t.height = height;
  const long double w = width, h = height;
  if (fit >= w * h) {  // one tile
    t.tileWidth = width;
    t.tileHeight = height;
  } else if (fit >= w) {  // bands of whole rows, as even as the count allows
    t.rows = divideUp(h, std::floor(fit / w));
    t.tileWidth = width;
    t.tileHeight = divideUp(h, t.rows);
  } else {  // runs of pixels within each row
    t.columns = divideUp(w, fit);
    t.tileWidth = divideUp(w, t.columns);
    t.tileHeight = 1;
  }
  t.columns = divideUp(w, t.tileWidth);
  t.rows = divideUp(h, t.tileHeight);
  t.poolBytes = 4 * kCounterWords + kNodeBytes * static_cast<std::size_t>(fragmentsPerPixel) *
                                        static_cast<std::size_t>(t.tileWidth) * static_cast<std::size_t>(t.tileHeight);
  return t;
}

std::vector<VolumeBand> planVolumeBands(const std::vector<double>& rowFragments, int width, double capacity,
                                        std::size_t maxPixels) {
  const int maxRows = std::max(1, static_cast<int>(std::min<std::size_t>(maxPixels / static_cast<std::size_t>(width),
                                                                         rowFragments.size())));
  std::vector<VolumeBand> bands;
  const int rows = static_cast<int>(rowFragments.size());
  for (int first = 0; first < rows;) {
    int end = first + 1;
    double load = rowFragments[static_cast<std::size_t>(first)];
    while (end < rows && end - first < maxRows && load + rowFragments[static_cast<std::size_t>(end)] <= capacity)
      load += rowFragments[static_cast<std::size_t>(end++)];
    bands.push_back({first, end});
    first = end;
  }
  return bands;
}

// The resolve programs' defines: the fragment lists' and their reads (volume_fragments.glsl).
static std::string resolveDefines() { return VolumeResolve::fragmentDefines() + "#define FRAGMENT_READS\n"; }

VolumeResolve::VolumeResolve(const GlFunctions& gl, const StorageBudget& budget)
    : gl_(gl), budget_(budget), pool_(gl), cut_(gl), pixelLists_(gl), rowCounts_(gl), nodeWords_(gl, GL_R32UI, 4) {
  singleProgram_ = linkComputeProgram(
      gl, {"volume_fragments.glsl", "volume_pieces.glsl", "volume_resolve_single.comp.glsl"},
      resolveDefines() + glslDefine("STAGES", static_cast<int>(kSortedResolveSlots.size())) +
          glslDefine("SORTED_MAX", kShortListCapacity));
  sortedProgram(0);  // most frames with lists need the first stage; the others link on first use
  longProgram_ = linkComputeProgram(
      gl, {"volume_fragments.glsl", "volume_pieces.glsl", "loop_budget.glsl", "volume_resolve.comp.glsl"},
      resolveDefines() + glslDefine("MAX_SEGMENTS", kMaxSegmentsPerPixel) +
          glslFloatDefine("OPAQUE_TRANSMITTANCE", kOpaqueTransmittance));
}

VolumeResolve::~VolumeResolve() {
  if (heads_) gl_.DeleteTextures(1, &heads_);
  if (unusedHeads_) gl_.DeleteTextures(1, &unusedHeads_);
}

std::string VolumeResolve::fragmentDefines() {
  return glslDefine("FRAGMENT_NODE_WORDS", kFragmentNodeWords) +
         glslDefine("PIXEL_LIST_REGIONS", static_cast<int>(kPixelListRegions));
}

VolumeTiling VolumeResolve::prepare(int width, int height, int fragmentsPerPixel, long double budgetBytes,
                                    int shortList) {
  // the resolves read the pool as a buffer texture, one texel per word
  const long double budget = std::min({budgetBytes > 0 ? budgetBytes : kDefaultVolumePoolBytes, budget_.limitBytes(),
                                       nodeWords_.maxBytes()});
  tiling_ = planVolumeTiles(width, height, fragmentsPerPixel, budget);
  budget_.require(static_cast<long double>(tiling_.poolBytes),
                  "volume blending of a " + std::to_string(tiling_.tileWidth) + "x" + std::to_string(tiling_.tileHeight) +
                      " tile with " + std::to_string(fragmentsPerPixel) + " fragments per pixel");
  budgetBytes_ = budget;
  poolBytes_ = tiling_.poolBytes;
  tiles_.clear();
  for (int row = 0; row < tiling_.rows; ++row)
    for (int column = 0; column < tiling_.columns; ++column) {
      const int x0 = column * tiling_.tileWidth, y0 = row * tiling_.tileHeight;
      tiles_.push_back({x0, y0, std::min(x0 + tiling_.tileWidth, width), std::min(y0 + tiling_.tileHeight, height)});
    }
  tilePixels_ = static_cast<std::size_t>(tiling_.tileWidth) * static_cast<std::size_t>(tiling_.tileHeight);
  shortList_ = shortList;
  if (!heads_ || width != width_ || height != height_) {
    if (heads_) gl_.DeleteTextures(1, &heads_);
    gl_.GenTextures(1, &heads_);
    gl_.BindTexture(GL_TEXTURE_2D, heads_);
    gl_.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, width, height);
    width_ = width;
    height_ = height;
  }
  // Once per frame: a tile's fragments touch only its own pixels' heads.
  gl_.ClearTexImage(heads_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kListEnd);
  counts_ = {};
  resolveSeconds_ = 0;
  return tiling_;
}

std::size_t VolumeResolve::expectedTileNodes() const { return (tiling_.poolBytes - 4 * kCounterWords) / kNodeBytes; }

std::vector<double> VolumeResolve::countedRows(GLuint countTexture) {
  // the rows' sums on the GPU (volume_row_counts.comp.glsl), so that only a word per row is read
  // back, not the whole RGBA32F texture
  if (!rowCountsProgram_.id()) rowCountsProgram_ = linkComputeProgram(gl_, {"volume_row_counts.comp.glsl"}, "");
  rowCounts_.ensure(4 * static_cast<std::size_t>(height_));
  fullBarrier(gl_);
  gl_.UseProgram(rowCountsProgram_.id());
  gl_.BindImageTexture(kColourUnit, countTexture, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  rowCounts_.bind(kRowCountsBinding);
  gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(height_), kResolveGroup), 1, 1);
  fullBarrier(gl_);
  std::vector<GLuint> counted(static_cast<std::size_t>(height_));
  rowCounts_.read(0, 4 * counted.size(), counted.data());
  return std::vector<double>(counted.begin(), counted.end());
}

void VolumeResolve::planBandsFrom(const std::vector<double>& rows, int firstRow) {
  counts_.countedFragments = 0;
  for (std::size_t y = static_cast<std::size_t>(firstRow); y < rows.size(); ++y)
    counts_.countedFragments += static_cast<std::size_t>(rows[y]);
  counts_.countedPlan = true;
  // Would prepare's tiles have overflowed? Counted from the first overflow up, one did. Counted
  // from the bottom, each band of its rows against its pool; tiles that cut rows into runs are
  // taken to overflow (a row's count does not say how its runs share it).
  counts_.expectedPlanOverflows = firstRow > 0;
  if (firstRow == 0) {
    const double capacity = static_cast<double>(expectedTileNodes());
    for (const Rect& t : tiles_) {  // still prepare's
      double load = 0;
      for (int y = t.y0; y < t.y1; ++y) load += rows[static_cast<std::size_t>(y)];
      if (t.x0 != 0 || t.x1 != width_ || load > capacity) counts_.expectedPlanOverflows = true;
    }
  }
  const std::size_t nodes = static_cast<std::size_t>((budgetBytes_ - 4.0L * kCounterWords) / kNodeBytes);
  const std::size_t listWords = static_cast<std::size_t>(budget_.limitBytes() / 4.0L) - kPixelListHeaderWords;
  const std::vector<VolumeBand> bands =
      planVolumeBands(std::vector<double>(rows.begin() + firstRow, rows.end()), width_,
                      static_cast<double>(nodes) * (1.0 - kBandHeadroom), listWords / kPixelListRegions);
  tiles_.clear();
  tilePixels_ = 0;
  for (const VolumeBand& b : bands) {
    tiles_.push_back({0, firstRow + b.first, width_, firstRow + b.end});
    tilePixels_ = std::max(tilePixels_, static_cast<std::size_t>(width_) * static_cast<std::size_t>(b.end - b.first));
  }
  poolBytes_ = 4 * kCounterWords + kNodeBytes * nodes;
}

void VolumeResolve::planBands(GLuint countTexture) { planBandsFrom(countedRows(countTexture), 0); }

void VolumeResolve::run(GLuint colourTexture, const std::function<void()>& drawTile,
                        const std::function<void()>& countTile) {
  // sized here, once the plan is final (prepare's, or planBands'), so that a frame does not
  // reallocate them twice; again if the first overflow replans the rest (below)
  std::size_t capacity = 0;
  const auto sizeStorage = [&] {
    pool_.ensure(poolBytes_);
    // A word per pixel of a tile and region (four sevenths of a pool that holds one node per pixel).
    pixelLists_.ensure(4 * (kPixelListHeaderWords + kPixelListRegions * tilePixels_));
    capacity = (poolBytes_ - 4 * kCounterWords) / kNodeBytes;
  };
  sizeStorage();
  // The plan's tiles in order, as a stack (last = next). A tile whose fragments did not all find
  // room in the pool is drawn again as two halves along its longer side, until each part fits or
  // is one pixel: the pool's capacity per tile is fixed, so halving the pixels doubles the room
  // per pixel. The order of the splits depends only on the counts, so the image is the same
  // whatever the thread count.
  std::vector<Rect> pending(tiles_.rbegin(), tiles_.rend());
  while (!pending.empty()) {
    const Rect r = pending.back();
    pending.pop_back();
    const GLuint counters[kCounterWords] = {0, static_cast<GLuint>(capacity), 0, 0};
    pool_.write(0, sizeof counters, counters);
    GLuint listHeader[kPixelListHeaderWords] = {};  // the region counts, then the capacity
    listHeader[kPixelListRegions] = static_cast<GLuint>(tilePixels_);
    pixelLists_.write(0, sizeof listHeader, listHeader);
    pixelLists_.bind(kPixelListsBinding);
    fullBarrier(gl_);
    gl_.BindImageTexture(kHeadsUnit, heads_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    pool_.bind(kPoolBinding);
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
    drawTile();
    gl_.Disable(GL_SCISSOR_TEST);
    fullBarrier(gl_);
    GLuint drawn[kCounterWords] = {0, 0, 0, 0};
    pool_.read(0, sizeof drawn, drawn);
    const int w = r.x1 - r.x0, h = r.y1 - r.y0;
    if (drawn[2] > 0 && w * h > 1) {
      // Undo the tile: its fallback colour (cleared as the frame was) and its lists. The
      // distance channel is a minimum, which a second draw leaves unchanged.
      const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      gl_.ClearTexSubImage(heads_, 0, r.x0, r.y0, 0, w, h, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &kListEnd);
      if (countTile && !counts_.countedPlan && counts_.redrawnTiles == 0 && r.x0 == 0 && r.x1 == width_) {
        // The expected plan's first overflow, on a band of whole rows: the rows below are
        // resolved, the rows from here up (this tile's included) not drawn yet. Count their
        // fragments into the colour texture's red channel there, cleared, and plan them as
        // bands, as planBands does.
        const int rows = height_ - r.y0;
        gl_.ClearTexSubImage(colourTexture, 0, 0, r.y0, 0, width_, rows, 1, GL_RGBA, GL_FLOAT, clear);
        fullBarrier(gl_);
        gl_.Enable(GL_SCISSOR_TEST);
        gl_.Scissor(0, r.y0, width_, rows);
        countTile();
        gl_.Disable(GL_SCISSOR_TEST);
        planBandsFrom(countedRows(colourTexture), r.y0);
        gl_.ClearTexSubImage(colourTexture, 0, 0, r.y0, 0, width_, rows, 1, GL_RGBA, GL_FLOAT, clear);
        fullBarrier(gl_);
        pending.assign(tiles_.rbegin(), tiles_.rend());
        sizeStorage();
        ++counts_.redrawnTiles;
        continue;
      }
      gl_.ClearTexSubImage(colourTexture, 0, r.x0, r.y0, 0, w, h, 1, GL_RGBA, GL_FLOAT, clear);
      fullBarrier(gl_);
      Rect a = r, b = r;
      if (w >= h)
        a.x1 = b.x0 = r.x0 + w / 2;
      else
        a.y1 = b.y0 = r.y0 + h / 2;
      pending.push_back(b);
      pending.push_back(a);
      ++counts_.redrawnTiles;
      continue;
    }
    const Stopwatch clock;
    resolveTile(colourTexture);
    resolveSeconds_ += clock.seconds();
    GLuint c[kCounterWords] = {0, 0, 0, 0};
    pool_.read(0, sizeof c, c);
    counts_.fragments += c[0];
    counts_.overflow += c[2];
    counts_.truncatedPixels += c[3];
    ++counts_.tiles;
  }
}

void VolumeResolve::bindUnused() {
  if (pool_.bytes() == 0) pool_.ensure(64);
  pool_.bind(kPoolBinding);
  if (pixelLists_.bytes() == 0) pixelLists_.ensure(64);
  pixelLists_.bind(kPixelListsBinding);
  if (!unusedHeads_) {
    gl_.GenTextures(1, &unusedHeads_);
    gl_.BindTexture(GL_TEXTURE_2D, unusedHeads_);
    gl_.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, 1, 1);
  }
  gl_.BindImageTexture(kHeadsUnit, unusedHeads_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

const GlProgram& VolumeResolve::sortedProgram(std::size_t stage) {
  GlProgram& program = sortedPrograms_[stage];
  if (!program.id())
    program =
        linkComputeProgram(gl_, {"volume_fragments.glsl", "volume_pieces.glsl", "volume_resolve_sorted.comp.glsl"},
                           resolveDefines() + sortedResolveDefines(stage));
  return program;
}

void VolumeResolve::resolveTile(GLuint colourTexture) {
  fullBarrier(gl_);
  const GLuint zero = 0;
  cut_.assign(&zero, sizeof zero);
  cut_.bind(kCutBinding);
  pixelLists_.bind(kPixelListsBinding);
  pool_.bind(kPoolBinding);
  nodeWords_.bind(kNodeWordsTextureUnit, pool_, poolBytes_);
  gl_.BindImageTexture(kHeadsUnit, heads_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  gl_.BindImageTexture(kColourUnit, colourTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  // Region 0: the pixels the particle pass listed. The first resolve composites the lists of one
  // segment and hands each longer one to the region of the sorted stage that fits it (stage i's is
  // region i + 1) or to the chunked resolve's, the last.
  GLuint counts[kPixelListRegions] = {};
  pixelLists_.read(0, sizeof counts, counts);
  if (counts[0] > 0) {
    gl_.UseProgram(singleProgram_.id());
    gl_.Uniform1i(singleProgram_.uniform("uShortList"), shortList_);
    gl_.DispatchCompute(groupsFor(counts[0], kResolveGroup), 1, 1);
    fullBarrier(gl_);
    pixelLists_.read(0, sizeof counts, counts);
  }
  for (std::size_t i = 0; i < kSortedResolveSlots.size(); ++i) {
    if (counts[i + 1] == 0) continue;
    gl_.UseProgram(sortedProgram(i).id());
    gl_.DispatchCompute(groupsFor(counts[i + 1], kResolveGroup), 1, 1);
    fullBarrier(gl_);
  }
  const GLuint chunked = counts[kPixelListRegions - 1];
  if (chunked > 0) {
    gl_.UseProgram(longProgram_.id());
    gl_.Uniform1i(longProgram_.uniform("uProbePasses"), kLoopProbePasses);
    gl_.DispatchCompute(groupsFor(chunked, kResolveGroup), 1, 1);
    fullBarrier(gl_);
  }
  gl_.Finish();
  checkGlError(gl_, "resolving the volume fragment lists");
  GLuint cut = 0;
  cut_.read(0, sizeof cut, &cut);
  counts_.cutPixels += cut;
  // Over 8 segments: the regions after the 8-segment stage's, the chunked one included.
  for (std::size_t r = 3; r < kPixelListRegions; ++r) counts_.midLists += counts[r];
  counts_.longLists += chunked;
}

}  // namespace cloudlut::render
