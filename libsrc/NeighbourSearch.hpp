// Spindrift — neighbour search on a uniform grid.
//
// Cell size = kernel support h. The cells are a lattice over the case's domain box; each
// build covers only the range of them its points occupy (the box leaves room for splashes and
// has several times more cells). Particles outside the box are clamped into the border cells
// (still correct — cells become supersets — only slower), so a runaway particle never makes
// the grid explode. Points are bucketed with a stable counting sort, so neighbour order
// depends only on the input, never on the thread count or the range a build covers.
//
// Periodic axes (Periodicity): the grid wraps around them and distances use the minimum
// image; a list built with periodicity carries a pointer to it so pair loops
// (forEachNeighbour) apply the same minimum image — at no cost for non-periodic cases.
//
// Lists are compact (CSR): for particle i, indices[offsets[i] .. offsets[i+1]) excluding i.
// The grid keeps its points in cell order as a structure of arrays, so the per-step list
// build scans contiguous memory without branches (gatherWithin); in one parallel region each
// thread fills its own persistent buffers, one a list, for chunks of its block of particles.
// The search serves particle systems (numbered as the scene numbers them, addSystem) and builds,
// at every build, the lists of exactly the (query, source) pairs of systems declared to interact
// (addInteraction): a fluid against itself and against every wall and body, a passive system
// against the fluid it is carried by. A system that is a source has a grid: a fixed wall's is
// built once, the others' at every build. Pairs never declared (wall against wall) are searched
// only on demand (listBetween). A source's query neighbours (the transpose of a list) are made
// on demand, for boundary models that sum over the fluid around each wall particle.
// sortOrder() gives a permutation along a Z-order (Morton) curve of the cells, used to re-sort
// the particle arrays every few steps for cache locality.
// Pair loops run on thread ranges of equal work (workRange), split by the threads' measured
// speeds; a thread done with its range takes the last chunks of the others' (claimChunk).
#pragma once

#include "Types.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <list>
#include <type_traits>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

namespace spindrift {

// Periodic directions of the domain: a particle leaving at min + length re-enters at min.
struct Periodicity {
    bool axis[3] = {false, false, false};
    Vec3 min = Vec3::Zero();
    Vec3 length = Vec3::Zero();

    bool any() const { return axis[0] || axis[1] || axis[2]; }
    // r_ij → its nearest periodic image.
    void minimumImage(Vec3& rij) const {
        for (int a = 0; a < 3; ++a)
            if (axis[a]) rij[a] -= length[a] * std::round(rij[a] / length[a]);
    }
    // Position → into [min, min + length) along periodic axes.
    void wrap(Vec3& x) const {
        for (int a = 0; a < 3; ++a)
            if (axis[a]) x[a] -= length[a] * std::floor((x[a] - min[a]) / length[a]);
    }
};

struct NeighbourList {
    std::vector<std::uint32_t> offsets; // size n + 1
    std::vector<Index> indices;
    const Periodicity* periodic = nullptr; // set when the domain has periodic axes

    std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
    std::uint32_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
    const Index* begin(std::size_t i) const { return indices.data() + offsets[i]; }
    const Index* end(std::size_t i) const { return indices.data() + offsets[i + 1]; }
    std::size_t totalPairs() const { return indices.size(); }
};

// Re-sorting the particles (new i = old order[i]) moves whole rows of a list: the offsets of
// the rows in the new order, and per-pair data (an entry per pair of 'list', in list order)
// copied into that order, each entry through map (the neighbour indices are renumbered so).
std::vector<std::uint32_t> permutedOffsets(const NeighbourList& list, const std::vector<Index>& order);
template <class T, class Map = std::identity>
void permuteRowData(const NeighbourList& list, const std::vector<Index>& order,
                    const std::vector<std::uint32_t>& newOffsets, const std::vector<T>& from, std::vector<T>& to,
                    Map map = {}) {
    to.resize(from.size());
    const std::size_t n = order.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        T* out = to.data() + newOffsets[i];
        for (std::uint32_t k = list.offsets[order[i]]; k < list.offsets[order[i] + 1]; ++k) *out++ = map(from[k]);
    }
}

class UniformGrid {
public:
    // Periodic axes span exactly [periodic.min, periodic.min + length) with at least 3 cells.
    // The lattice over the domain has at most maxCellsAlong cells along an axis (the reach of the
    // space-filling curve's 21 bits) and maxCells in all (std::length_error beyond); its cells take
    // memory only where a build's points are.
    void setup(Scalar cellSize, int dimension, const Vec3& domainMin, const Vec3& domainMax,
               const Periodicity& periodic = {});
    static constexpr double maxCellsAlong = 2097152; // 2^21
    static constexpr double maxCells = 2e8;
    // Cells of the lattice along a (non-periodic) axis spanning 'extent' (in double: a domain of any
    // size is measured, never overflows an int).
    static double cellsAlong(double extent, Scalar cellSize) {
        return std::ceil(std::max(extent, 0.0) * double(Scalar(1) / cellSize)) + 1;
    }
    void build(const std::vector<Vec3>& points);
    // The built points were renumbered, point k now newIndexOf[k], in an order that keeps the
    // points of each cell in their index order: the grid is then that of a build on them.
    void relabel(const std::vector<Index>& newIndexOf);

    // Calls f(j) for every point j of the built set with |p − x_j| < radius (radius <= cell size).
    template <class F>
    void forEachWithin(const Vec3& p, const std::vector<Vec3>& points, Scalar radius, F&& f) const {
        const Scalar r2 = radius * radius;
        if (periodic_.any()) {
            int c[3];
            cellCoords(p, c);
            forEachWithinPeriodic(p, c, points, r2, f);
            return;
        }
        RowRange rows[9];
        const int nRows = candidateRows(p, rows);
        for (int r = 0; r < nRows; ++r)
            for (Index k = rows[r].first; k < rows[r].last; ++k) {
                const Index j = sorted_[k];
                if ((p - points[j]).squaredNorm() < r2) f(j);
            }
    }

    // Writes every point k of the built set with |p − x_k|² < r2, k ≠ self, to the array
    // reserve(room) returns (room for 'room' indices: the points in the cells around p, plus
    // scanSpill slots a vector store may write past the last point kept), and returns how many.
    // Same points, in the same order, as forEachWithin on a non-periodic grid; the scan runs
    // over the grid's own cell-ordered copy of the positions without branches (the hot loop of
    // the step's lists).
    template <class Reserve> std::size_t gatherWithin(const Vec3& p, Scalar r2, Index self, Reserve&& reserve) const {
        RowRange rows[9];
        const int nRows = candidateRows(p, rows);
        std::size_t candidates = 0;
        for (int r = 0; r < nRows; ++r) candidates += rows[r].last - rows[r].first;
        Index* out = reserve(candidates + scanSpill);
        std::size_t count = 0;
        for (int r = 0; r < nRows; ++r) count += scanRow(rows[r], p, r2, self, out + count);
        return count;
    }

    // Cell of p (points outside the grid are clamped into the border cells).
    void cellCoords(const Vec3& p, int c[3]) const { coords(p, first_, dims_, c); }
    // Z-order (Morton) code of p's lattice cell (independent of the range the last build covers).
    std::uint64_t mortonCode(const Vec3& p) const;
    std::size_t cellCount() const { return cellStart_.empty() ? 0 : cellStart_.size() - 1; }

    // Slots past the found points that gatherWithin may overwrite (a vector of indices less one).
#if defined(__AVX512F__) && defined(__AVX512VL__)
    static constexpr std::size_t scanSpill = 64 / sizeof(Scalar) - 1;
#else
    static constexpr std::size_t scanSpill = 0;
#endif

private:
    // Cell of p in the lattice of the set-up domain box (clamped into it).
    void latticeCoords(const Vec3& p, int c[3]) const {
        static constexpr int none[3] = {0, 0, 0};
        coords(p, none, latticeDims_, c);
    }
    // Cell of p within cells first .. first + dims − 1 of the set-up lattice, clamped into them
    // (NaN to the first); periodic axes wrap.
    void coords(const Vec3& p, const int first[3], const int dims[3], int c[3]) const {
        for (int a = 0; a < 3; ++a) {
            const Scalar s = (p[a] - origin_[a]) * invCell_[a];
            if (periodic_.axis[a] && std::isfinite(s)) {
                const long k = long(std::floor(s)) % dims[a];
                c[a] = int(k < 0 ? k + dims[a] : k);
                continue;
            }
            const int last = first[a] + dims[a] - 1;
            c[a] = std::max((s >= Scalar(0) ? (s < Scalar(last) ? int(s) : last) : 0) - first[a], 0);
        }
        if (dim_ == 2) c[2] = 0;
    }

    struct RowRange {
        Index first, last; // slots in sorted_ of a row of up to three cells along x
    };
    // Writes the points of one row within r2 of p (except self) to out; returns how many. With
    // AVX-512 eight (double) or sixteen (float) points are tested at once and their indices
    // compressed, the row's last block with masked loads; without AVX-512 a branch-free scalar loop.
    std::size_t scanRow(RowRange row, const Vec3& p, Scalar r2, Index self, Index* out) const {
        const Scalar px = p[0], py = p[1], pz = p[2];
        const Scalar* sx = cellX_.data();
        const Scalar* sy = cellY_.data();
        const Scalar* sz = cellZ_.data();
        const Index* sorted = sorted_.data();
        std::size_t count = 0;
        Index k = row.first;
#if defined(__AVX512F__) && defined(__AVX512VL__)
        // the row's last, partial block with masked loads: no scalar remainder
        if constexpr (std::is_same_v<Scalar, double>) {
            const __m512d vx = _mm512_set1_pd(px), vy = _mm512_set1_pd(py), vz = _mm512_set1_pd(pz);
            const __m512d vr2 = _mm512_set1_pd(r2);
            const __m256i vself = _mm256_set1_epi32(int(self));
            for (; k < row.last; k += 8) {
                const Index left = row.last - k;
                const __mmask8 valid = left >= 8 ? __mmask8(0xFF) : __mmask8((1u << left) - 1);
                const __m512d dx = _mm512_sub_pd(vx, _mm512_maskz_loadu_pd(valid, sx + k));
                const __m512d dy = _mm512_sub_pd(vy, _mm512_maskz_loadu_pd(valid, sy + k));
                const __m512d dz = _mm512_sub_pd(vz, _mm512_maskz_loadu_pd(valid, sz + k));
                const __m512d d2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
                const __m256i j = _mm256_maskz_loadu_epi32(valid, sorted + k);
                const __mmask8 keep =
                    _mm512_mask_cmp_pd_mask(valid, d2, vr2, _CMP_LT_OQ) & ~_mm256_cmpeq_epi32_mask(j, vself);
                // compress in a register, store all eight lanes (the lanes past the kept ones are
                // overwritten later; gatherWithin reserves room for them). A masked
                // compress-store to memory is microcoded on some CPUs (AMD Zen 4): far slower.
                _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + count), _mm256_maskz_compress_epi32(keep, j));
                count += std::size_t(__builtin_popcount(keep));
            }
        } else {
            const __m512 vx = _mm512_set1_ps(px), vy = _mm512_set1_ps(py), vz = _mm512_set1_ps(pz);
            const __m512 vr2 = _mm512_set1_ps(r2);
            const __m512i vself = _mm512_set1_epi32(int(self));
            for (; k < row.last; k += 16) {
                const Index left = row.last - k;
                const __mmask16 valid = left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1);
                const __m512 dx = _mm512_sub_ps(vx, _mm512_maskz_loadu_ps(valid, sx + k));
                const __m512 dy = _mm512_sub_ps(vy, _mm512_maskz_loadu_ps(valid, sy + k));
                const __m512 dz = _mm512_sub_ps(vz, _mm512_maskz_loadu_ps(valid, sz + k));
                const __m512 d2 = _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
                const __m512i j = _mm512_maskz_loadu_epi32(valid, sorted + k);
                const __mmask16 keep =
                    _mm512_mask_cmp_ps_mask(valid, d2, vr2, _CMP_LT_OQ) & ~_mm512_cmpeq_epi32_mask(j, vself);
                _mm512_storeu_si512(out + count, _mm512_maskz_compress_epi32(keep, j));
                count += std::size_t(__builtin_popcount(keep));
            }
        }
#endif
        for (; k < row.last; ++k) {
            const Scalar dx = px - sx[k], dy = py - sy[k], dz = pz - sz[k];
            const Index j = sorted[k];
            out[count] = j;
            count += std::size_t((dx * dx + dy * dy + dz * dz < r2) & (j != self));
        }
        return count;
    }

    // The rows of cells around p (non-periodic grids): 9 in 3D, 3 in 2D.
    int candidateRows(const Vec3& p, RowRange rows[9]) const {
        int c[3];
        cellCoords(p, c);
        const int zLo = dim_ == 3 ? std::max(c[2] - 1, 0) : 0;
        const int zHi = dim_ == 3 ? std::min(c[2] + 1, dims_[2] - 1) : 0;
        const int yLo = std::max(c[1] - 1, 0), yHi = std::min(c[1] + 1, dims_[1] - 1);
        const int xLo = std::max(c[0] - 1, 0), xHi = std::min(c[0] + 1, dims_[0] - 1);
        int n = 0;
        for (int z = zLo; z <= zHi; ++z)
            for (int y = yLo; y <= yHi; ++y) {
                const std::size_t row = (std::size_t(z) * dims_[1] + y) * dims_[0];
                rows[n++] = {cellStart_[row + xLo], cellStart_[row + xHi + 1]};
            }
        return n;
    }

    template <class F>
    void forEachWithinPeriodic(const Vec3& p, const int c[3], const std::vector<Vec3>& points, Scalar r2,
                               F&& f) const {
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            const bool used = a < dim_;
            lo[a] = !used ? 0 : periodic_.axis[a] ? c[a] - 1 : std::max(c[a] - 1, 0);
            hi[a] = !used ? 0 : periodic_.axis[a] ? c[a] + 1 : std::min(c[a] + 1, dims_[a] - 1);
        }
        auto wrapped = [&](int v, int a) { return periodic_.axis[a] ? (v + dims_[a]) % dims_[a] : v; };
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    const std::size_t cell =
                        (std::size_t(wrapped(z, 2)) * dims_[1] + wrapped(y, 1)) * dims_[0] + wrapped(x, 0);
                    for (Index k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
                        const Index j = sorted_[k];
                        Vec3 d = p - points[j];
                        periodic_.minimumImage(d);
                        if (d.squaredNorm() < r2) f(j);
                    }
                }
    }

    Vec3 origin_ = Vec3::Zero();
    Vec3 invCell_ = Vec3::Ones();
    Periodicity periodic_;
    int dim_ = 3;
    int latticeDims_[3] = {1, 1, 1}; // cells of the set-up domain box
    int first_[3] = {0, 0, 0};       // the built grid: cells first_ .. first_ + dims_ − 1 of that lattice,
    int dims_[3] = {1, 1, 1};        // the range the points occupy (periodic axes: all)
    std::vector<Index> cellStart_; // size cells + 1
    std::vector<Index> sorted_;    // point indices bucketed by cell
    std::vector<Index> cellOf_;    // scratch
    std::vector<std::size_t> blockPoints_; // scratch: the points in each thread's block of cells
    std::vector<Scalar> cellX_, cellY_, cellZ_; // positions in sorted_ order (structure of arrays)
};

class NeighbourSearch;

// A query system's neighbour lists, one per source system it interacts with (its own first,
// when it is a source of itself), and the balanced parallel schedule of the passes over its
// particles.
//
// Pair loops run on thread ranges of equal work (workRange): thread t of T takes
// [first, last) = workRange(t, T), with about the same number of neighbours as every other
// thread (particles near walls have more). PairWork::Own balances the system's own pairs alone,
// for passes that visit no other system. The split follows the threads' measured speeds: the
// balanced passes report how long each thread took for its range (recordTime), and each build
// gives a thread a share of the work in proportion to its speed, averaged over the last steps.
// On a shared or virtual machine one core is often slower than the other for tens of steps at a
// time; a thread there gets less work instead of the others waiting for it. Which thread
// computes a particle never changes a result, so the results stay independent of the split.
class QueryLists {
public:
    enum class PairWork { All, Own };

    std::size_t system() const { return system_; }
    // The particles the lists have rows for (the query system's own, not its ghosts).
    std::size_t size() const { return particles_; }
    // The source systems, in list order, and each one's list.
    std::size_t sourceCount() const { return sources_.size(); }
    std::size_t source(std::size_t k) const { return sources_[k]; }
    const NeighbourList& list(std::size_t k) const { return lists_[k]; }
    // The list of source system s (null when the query does not interact with it).
    const NeighbourList* find(std::size_t s) const {
        for (std::size_t k = 0; k < sources_.size(); ++k)
            if (sources_[k] == s) return &lists_[k];
        return nullptr;
    }
    // The system's neighbours among its own particles (it must be a source of itself).
    const NeighbourList& own() const { return lists_[0]; }
    bool hasOwn() const { return !sources_.empty() && sources_[0] == system_; }
    // How many neighbours particle i has in the other source systems.
    std::uint32_t otherNeighbourCount(std::size_t i) const { return otherPairsBefore_[i + 1] - otherPairsBefore_[i]; }
    // Changes whenever the lists are built again or relabelled (for data kept per pair).
    long stamp() const { return stamp_; }

    std::pair<std::size_t, std::size_t> workRange(int t, int threads, PairWork work = PairWork::All) const {
        return rangeOf(work == PairWork::Own ? ownWorkRanges_ : workRanges_, t, threads);
    }
    // The thread count the ranges were balanced for (the last build's).
    int workRangeThreads() const { return int(workRanges_.size()) - 1; }
    // Thread t of a region balanced with workRange took 'seconds' for [first, last). Each
    // thread writes only its own slot; ignored when the thread count is not the build's.
    void recordTime(int t, int threads, PairWork work, std::size_t first, std::size_t last, double seconds) const {
        recordWork(t, threads, pairsIn(first, last, work), seconds);
    }
    // The same for a thread that did 'pairs' of work (pairsIn of the chunks it took) in 'seconds'.
    void recordWork(int t, int threads, double pairs, double seconds) const {
        if (threads != workRangeThreads() || threads < 2) return;
        ThreadClock& c = passSpeeds_.clocks[t];
        c.work += pairs;
        c.seconds += seconds;
    }
    // The pair work of particles [first, last), in the units of the split.
    double pairsIn(std::size_t first, std::size_t last, PairWork work) const {
        return double(pairWork(last, work) - pairWork(first, work));
    }

    // Sharing the tail of a balanced region (forEachParticleBalanced). The split follows the
    // speeds of the last steps, but a core is often slowed for a few microseconds at random (by
    // another process, an interrupt), and the others then wait at the region's end: 4-7 % of a
    // pass on this project's 2-core machines. So each thread takes its range in chunks, a
    // quarter of what is left at a time and never fewer than minChunk particles, from an atomic
    // cursor; a thread done with its own range takes chunks of the others'. Each region gets a
    // new number (beginRegion, called by the thread that opens it), and the first thread to
    // claim a range in it starts that range's cursor.
    std::uint32_t beginRegion() const { return ++regions_ != 0 ? regions_ : ++regions_; }
    bool sharesChunks(int threads) const { return threads <= int(cursors_.size()); }
    // The next chunk [first, last) of thread owner's range in region 'region'; empty
    // (first == last) when the range is done.
    std::pair<std::size_t, std::size_t> claimChunk(int owner, int threads, PairWork work, std::uint32_t region) const {
        const auto [first, last] = workRange(owner, threads, work);
        return claimChunk(owner, first, last, region);
    }

    // The relative speeds the ranges were split by (mean 1), for tests and logs.
    const std::vector<double>& threadSpeeds() const { return passSpeeds_.speed; }
    // The same for the list build's own split (searchRange): the search's cost per pair of the
    // last lists differs from the passes' (it scans cells, so particles with few neighbours
    // cost more per pair), and its split learns that from its own times.
    const std::vector<double>& searchThreadSpeeds() const { return searchSpeeds_.speed; }
    std::pair<std::size_t, std::size_t> searchRange(int t, int threads) const {
        return rangeOf(searchRanges_, t, threads);
    }

private:
    friend class NeighbourSearch;
    std::size_t system_ = 0, particles_ = 0;
    std::vector<std::size_t> sources_;
    std::vector<NeighbourList> lists_;
    std::vector<std::uint32_t> otherPairsBefore_; // pairs in the other systems' lists before particle i
    long stamp_ = -1;
    bool built_ = false, builtAhead_ = false;
    std::vector<Vec3> builtPoints_; // the system's points at the last build or build ahead
    // threads + 1 bounds: the passes' (workRange) and the list build's (searchRange)
    std::vector<std::size_t> workRanges_, ownWorkRanges_, searchRanges_;
    struct alignas(64) ThreadClock { // one cache line each: the threads write them concurrently
        double work = 0, seconds = 0;
    };
    struct ThreadSpeeds {               // of one kind of region
        std::vector<ThreadClock> clocks; // since the last build
        std::vector<double> speed;       // relative speed of each thread, mean 1
        void update(int threads);        // from the clocks, which it then resets
    };
    struct alignas(64) ChunkCursor {                 // one cache line each
        std::atomic<std::uint64_t> state{0};          // region << 32 | next particle
        ChunkCursor() = default;
        ChunkCursor(const ChunkCursor&) : state(0) {} // copies start afresh: region numbers are never 0
        ChunkCursor& operator=(const ChunkCursor&) {
            state = 0;
            return *this;
        }
    };
    mutable std::vector<ChunkCursor> cursors_; // one a thread, sized by balanceWork (and gatherLists)
    mutable std::uint32_t regions_ = 0;
    static constexpr std::size_t minChunk = 16;
    mutable ThreadSpeeds passSpeeds_; // the balanced passes' (recordTime)
    ThreadSpeeds searchSpeeds_;       // the list build's
    static constexpr std::size_t perParticle = 8; // cost of a particle's own work, in pairs
    // Work before particle i: its pairs (all, or its own system's only) plus perParticle each.
    std::size_t pairWork(std::size_t i, PairWork work) const {
        const std::size_t own = hasOwn() ? std::size_t(lists_[0].offsets[i]) : 0;
        return own + (work == PairWork::All ? otherPairsBefore_[i] : 0) + perParticle * i;
    }
    std::pair<std::size_t, std::size_t> rangeOf(const std::vector<std::size_t>& ranges, int t, int threads) const {
        const std::size_t n = particles_;
        if (threads == int(ranges.size()) - 1 && ranges.back() == n) return {ranges[t], ranges[t + 1]};
        return {n * t / threads, n * (t + 1) / threads};
    }
    void countOtherPairs();
    void balanceWork(); // over the threads the next passes run on
    // The next chunk of [first, last), the range of thread owner, in region 'region'.
    std::pair<std::size_t, std::size_t> claimChunk(int owner, std::size_t first, std::size_t last,
                                                   std::uint32_t region) const {
        std::atomic<std::uint64_t>& cursor = cursors_[owner].state;
        const std::uint64_t tag = std::uint64_t(region) << 32, low = 0xffffffffULL;
        std::uint64_t state = cursor.load(std::memory_order_relaxed);
        // a failed exchange leaves in 'state' what another thread stored: this region's start
        if ((state & ~low) != tag && cursor.compare_exchange_strong(state, tag | first, std::memory_order_relaxed))
            state = tag | first;
        const std::size_t next = std::size_t(state & low);
        if (next >= last) return {last, last};
        const std::size_t size = std::max(minChunk, (last - next) / 4);
        const std::size_t begin = std::size_t(cursor.fetch_add(size, std::memory_order_relaxed) & low);
        return {std::min(begin, last), std::min(begin + size, last)};
    }
};

class NeighbourSearch {
public:
    using PairWork = QueryLists::PairWork;
    // At most this many source systems a query system (its own and one per wall or body).
    static constexpr int maxLists = 16;

    // radius = kernel support h; domain = box the particles are expected to stay in.
    void setup(Scalar radius, int dimension, const Vec3& domainMin, const Vec3& domainMax,
               const Periodicity& periodic = {});
    const Periodicity& periodicity() const { return periodic_; }
    Scalar radius() const { return radius_; }
    // The box the particles are expected to stay in (setup)
    const Vec3& domainMin() const { return domainMin_; }
    const Vec3& domainMax() const { return domainMax_; }

    // Registers the next system (its number is the count before): the search reads its
    // positions through the pointer at every build; a fixed system's grid is built once.
    std::size_t addSystem(const std::vector<Vec3>* positions, bool fixed);
    std::size_t systemCount() const { return systems_.size(); }
    // The system's positions moved outside a build (a fixed wall placed once more, a system
    // resized): its grid is built again at the next build.
    void positionsChanged(std::size_t system) { systems_[system].gridBuilt = false; }
    // The system's particles [owned, size) are ghosts: sources only (rows for [0, owned)).
    void setOwnedSize(std::size_t system, std::size_t owned) { systems_[system].owned = owned; }
    // Declares that particles of 'query' need their neighbours among those of 'source' (the
    // same system: its own neighbours, each particle itself excluded). Lists are built for
    // the declared pairs only. Idempotent.
    void addInteraction(std::size_t query, std::size_t source);
    bool interacts(std::size_t query, std::size_t source) const;

    // Rebuilds the grids of the moving systems and every declared list at the systems' current
    // positions; a query system whose lists were built ahead at exactly its current positions
    // (buildAhead), with no other source moving, keeps them.
    void build();
    // The lists of 'query' (and its grid) for positions a model predicts the next step to start
    // from (dfsph's check): the search remembers them, and builtAt() tells whether a later state
    // is exactly there, so that the step need not search again.
    void buildAhead(std::size_t query, const std::vector<Vec3>& predicted);
    bool builtAt(std::size_t query, const std::vector<Vec3>& positions) const;
    // Whether the lists of 'query' were made at exactly these positions (the last build's, or a
    // build ahead's; relabelled by permute()), the other sources where they were then (true for
    // a system that queries nothing).
    bool listsAt(std::size_t query, const std::vector<Vec3>& positions) const;

    // Permutation that orders points along the Z-order curve of the grid cells (stable: the
    // points of a cell keep their order).
    std::vector<Index> sortOrder(const std::vector<Vec3>& points) const;
    // System k's particles of the last build were reordered, new i = old order[i], by a
    // permutation that keeps the points of a cell in their order (sortOrder's): relabels its
    // rows, the lists that name its particles and its grid, which are then those a build on the
    // reordered points gives, pair for pair and in the same order, for less than a build costs.
    void permute(std::size_t system, const std::vector<Index>& order);

    // System query's particles against system source's (each particle's neighbours, itself
    // excluded when query == source), computed on demand, e.g. for wall volumes at set-up.
    NeighbourList listBetween(std::size_t query, std::size_t source) const;
    // The query neighbours of each particle of 'source': the transpose of the list (query,
    // source), each row in ascending query index (so independent of the thread count), computed
    // on first use after a build. Not to be called inside a parallel region.
    const NeighbourList& reverseNeighbours(std::size_t query, std::size_t source) const;

    // The lists of query system q (every system has an entry; a system that queries nothing has
    // no sources).
    const QueryLists& of(std::size_t query) const { return systems_[query].query; }
    // The list (query, source); the pair must have been declared.
    const NeighbourList& neighbours(std::size_t query, std::size_t source) const;
    // How many times build() ran (for tests: a search a step saves shows here).
    long builds() const { return builds_; }
    const UniformGrid& grid(std::size_t system) const { return systems_[system].grid; }

    // f(j, r) for every particle j of 'system' within 'radius' (at most h) of p, at the
    // system's positions as they are now: a grid of them is built when 'version' differs from
    // the one it was built for (callers pass a number that changes whenever the particles move,
    // Scene::stateVersion). For function objects, which sample between the steps' searches.
    template <class F>
    void forEachWithin(std::size_t system, const Vec3& p, Scalar radius, long version, F&& f) const {
        const SystemEntry& e = systems_[system];
        if (e.pointGridVersion != version) {
            if (!e.pointGridSetUp) e.pointGrid.setup(radius_, dim_, domainMin_, domainMax_, periodic_);
            e.pointGridSetUp = true;
            e.pointGrid.build(*e.positions);
            e.pointGridVersion = version;
        }
        const std::vector<Vec3>& x = *e.positions;
        e.pointGrid.forEachWithin(p, x, radius, [&](Index j) {
            Vec3 d = p - x[j];
            periodic_.minimumImage(d);
            f(j, d.norm());
        });
    }

private:
    Scalar radius_ = 0;
    int dim_ = 3;
    Vec3 domainMin_ = Vec3::Zero(), domainMax_ = Vec3::Zero();
    Periodicity periodic_;
    struct SystemEntry {
        const std::vector<Vec3>* positions = nullptr;
        std::size_t owned = std::size_t(-1); // rows for [0, owned); -1: every particle
        bool fixed = false, isSource = false, gridBuilt = false;
        UniformGrid grid;
        QueryLists query;
        struct Reverse {
            std::size_t query;
            NeighbourList list;
            long stamp;
        };
        mutable std::list<Reverse> reverse; // transposes made on demand (reverseNeighbours)
        mutable UniformGrid pointGrid;        // forEachWithin's
        mutable long pointGridVersion = std::numeric_limits<long>::min();
        mutable bool pointGridSetUp = false;
        std::size_t rows() const { return std::min(owned, positions->size()); }
    };
    std::vector<SystemEntry> systems_;
    UniformGrid lattice_; // the domain's lattice (Morton codes of sortOrder); never built
    long builds_ = 0, stamps_ = 0;
    // kept between steps, no allocation per step: [lists t + l] thread t's rows of list l
    std::vector<std::vector<Index>> threadBuffers_;
    struct GatherChunk {          // particles [first, last) gathered by one thread
        std::size_t first, last;
        std::size_t start[maxLists], end[maxLists]; // their rows in the thread's buffers
        std::size_t target[maxLists];               // and in the lists
        bool inPlace;                 // gathered straight into the lists (the first thread's leading chunks)
    };
    std::vector<std::vector<GatherChunk>> threadChunks_; // kept between builds
    std::vector<GatherChunk*> chunkOrder_;

    void buildGrid(SystemEntry& e, const std::vector<Vec3>& points);
    // The lists of query system q with its own positions 'points'.
    void buildLists(SystemEntry& q, const std::vector<Vec3>& points);
    template <class Gather> void gatherLists(QueryLists& q, std::size_t n, int listCount, Gather&& gather);
};

// The transpose of a list of rows over 'columns' points: row c of the result holds every i
// whose row holds c, in ascending order (so independent of the thread count).
NeighbourList transposeList(const NeighbourList& list, std::size_t columns);

namespace detail {
// f(i) for i in [first, last): one copy of f's code for every path of forEachParticleBalanced.
// Inlined into each path, f was compiled twice, and GCC may contract a product and a sum into
// a fused multiply-add in one copy but not the other: the single-precision dfsph then computed
// different bits on one thread (the plain range) than on two (the chunks).
template <class F> [[gnu::noinline]] void forEachInRange(std::size_t first, std::size_t last, F& f) {
    for (std::size_t i = first; i < last; ++i) f(i);
}
} // namespace detail

// Calls f(i) for every particle i of a query system in parallel, each thread over its
// workRange and then over what is left of the others' (claimChunk): for pair loops over the
// step's lists (deterministic: every i is computed by one thread alone, and f(i) writes only
// i's results).
template <class F>
void forEachParticleBalanced(const QueryLists& q, F&& f, QueryLists::PairWork work = QueryLists::PairWork::All) {
#ifdef _OPENMP
    const std::uint32_t region = q.beginRegion();
#pragma omp parallel
    {
        const int t = omp_get_thread_num(), threads = omp_get_num_threads();
        const double start = omp_get_wtime();
        if (threads > 1 && q.sharesChunks(threads)) {
            double pairs = 0;
            for (int k = 0; k < threads; ++k) { // its own range first, then the others' tails
                const int owner = (t + k) % threads;
                for (auto chunk = q.claimChunk(owner, threads, work, region); chunk.first < chunk.second;
                     chunk = q.claimChunk(owner, threads, work, region)) {
                    detail::forEachInRange(chunk.first, chunk.second, f);
                    pairs += q.pairsIn(chunk.first, chunk.second, work);
                }
            }
            q.recordWork(t, threads, pairs, omp_get_wtime() - start);
        } else {
            const auto [first, last] = q.workRange(t, threads, work);
            detail::forEachInRange(first, last, f);
            q.recordTime(t, threads, work, first, last, omp_get_wtime() - start);
        }
    }
#else
    detail::forEachInRange(0, q.size(), f);
    (void)work;
#endif
}

// Builds a CSR list for n query points, calling query(i, push) where push(j) appends a
// neighbour; parallel over contiguous blocks, deterministic.
template <class Query> void buildNeighbourList(std::size_t n, NeighbourList& list, Query&& query);

} // namespace spindrift

#include "NeighbourSearch.tpp"
