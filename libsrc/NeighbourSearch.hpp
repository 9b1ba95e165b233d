// Spindrift — neighbour search on a uniform grid.
//
// Cell size = kernel support h. The grid covers the case's domain box; particles outside it
// are clamped into the border cells (still correct — cells become supersets — only slower),
// so a runaway particle never makes the grid explode. Points are bucketed with a stable
// counting sort, so neighbour order depends only on the input, never on the thread count.
//
// Periodic axes (Periodicity): the grid wraps around them and distances use the minimum
// image; a list built with periodicity carries a pointer to it so pair loops
// (forEachNeighbour) apply the same minimum image — at no cost for non-periodic cases.
//
// Lists are compact (CSR): for particle i, indices[offsets[i] .. offsets[i+1]) excluding i.
// Fluid–fluid and fluid–boundary lists are rebuilt each step; the static boundary grid is
// built once and boundary–boundary pairs are never searched during the run.
// sortOrder() gives a permutation along a Z-order (Morton) curve of the cells, used to re-sort
// the particle arrays every few steps for cache locality.
#pragma once

#include "Types.hpp"

#include <cmath>

#include <vector>

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

class UniformGrid {
public:
    // Periodic axes span exactly [periodic.min, periodic.min + length) with at least 3 cells.
    void setup(Scalar cellSize, int dimension, const Vec3& domainMin, const Vec3& domainMax,
               const Periodicity& periodic = {});
    void build(const std::vector<Vec3>& points);

    // Calls f(j) for every point j of the built set with |p − x_j| < radius (radius <= cell size).
    template <class F>
    void forEachWithin(const Vec3& p, const std::vector<Vec3>& points, Scalar radius, F&& f) const {
        const Scalar r2 = radius * radius;
        int c[3];
        cellCoords(p, c);
        if (periodic_.any()) {
            forEachWithinPeriodic(p, c, points, r2, f);
            return;
        }
        const int zLo = dim_ == 3 ? std::max(c[2] - 1, 0) : 0;
        const int zHi = dim_ == 3 ? std::min(c[2] + 1, dims_[2] - 1) : 0;
        const int yLo = std::max(c[1] - 1, 0), yHi = std::min(c[1] + 1, dims_[1] - 1);
        const int xLo = std::max(c[0] - 1, 0), xHi = std::min(c[0] + 1, dims_[0] - 1);
        for (int z = zLo; z <= zHi; ++z)
            for (int y = yLo; y <= yHi; ++y) {
                const std::size_t row = (std::size_t(z) * dims_[1] + y) * dims_[0];
                const Index first = cellStart_[row + xLo], last = cellStart_[row + xHi + 1];
                for (Index k = first; k < last; ++k) {
                    const Index j = sorted_[k];
                    if ((p - points[j]).squaredNorm() < r2) f(j);
                }
            }
    }

    void cellCoords(const Vec3& p, int c[3]) const;
    std::uint64_t mortonCode(const Vec3& p) const;
    std::size_t cellCount() const { return cellStart_.empty() ? 0 : cellStart_.size() - 1; }

private:
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
    int dims_[3] = {1, 1, 1};
    std::vector<Index> cellStart_; // size cells + 1
    std::vector<Index> sorted_;    // point indices bucketed by cell
    std::vector<Index> cellOf_;    // scratch
};

class NeighbourSearch {
public:
    // radius = kernel support h; domain = box the particles are expected to stay in.
    void setup(Scalar radius, int dimension, const Vec3& domainMin, const Vec3& domainMax,
               const Periodicity& periodic = {});
    const Periodicity& periodicity() const { return periodic_; }
    // Static boundary points: their grid is built once, here.
    void setBoundary(const std::vector<Vec3>& boundaryPoints);

    // Rebuilds fluid–fluid and fluid–boundary lists for the current fluid positions.
    void build(const std::vector<Vec3>& fluidPoints);

    // Permutation that orders points along the Z-order curve of the grid cells.
    std::vector<Index> sortOrder(const std::vector<Vec3>& points) const;

    // Boundary–boundary list (each boundary point's boundary neighbours, self excluded),
    // computed on demand, e.g. for boundary volumes at set-up.
    NeighbourList boundaryBoundaryList() const;

    const NeighbourList& fluidNeighbours() const { return fluidFluid_; }
    const NeighbourList& boundaryNeighbours() const { return fluidBoundary_; }
    const UniformGrid& fluidGrid() const { return fluidGrid_; }
    const UniformGrid& boundaryGrid() const { return boundaryGrid_; }
    Scalar radius() const { return radius_; }
    bool hasBoundary() const { return !boundaryPoints_.empty(); }

private:
    Scalar radius_ = 0;
    int dim_ = 3;
    Periodicity periodic_;
    UniformGrid fluidGrid_, boundaryGrid_;
    std::vector<Vec3> boundaryPoints_;
    NeighbourList fluidFluid_, fluidBoundary_;
};

// Builds a CSR list for n query points, calling query(i, push) where push(j) appends a
// neighbour; parallel over contiguous blocks, deterministic.
template <class Query> void buildNeighbourList(std::size_t n, NeighbourList& list, Query&& query);

} // namespace spindrift

#include "NeighbourSearch.tpp"
