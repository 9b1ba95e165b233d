#include "SurfaceSampling.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace spindrift {

void PointGrid::cellOf(const Vec3& p, long c[3]) const {
    for (int a = 0; a < 3; ++a) c[a] = a < dim_ ? long(std::floor(double(p[a]) / cell_)) : 0;
}

std::uint64_t PointGrid::key(long i, long j, long k) const {
    // 21 bits an axis, offset: cells far apart may share a key, which only costs a comparison
    const auto part = [](long v) { return std::uint64_t(v + (1L << 20)) & ((1ULL << 21) - 1); };
    return (part(k) << 42) | (part(j) << 21) | part(i);
}

void PointGrid::add(const Vec3& p) {
    long c[3];
    cellOf(p, c);
    cells_[key(c[0], c[1], c[2])].push_back(std::uint32_t(points_.size()));
    points_.push_back(p);
}

double PointGrid::nearest(const Vec3& p, int reach) const {
    long c[3];
    cellOf(p, c);
    double best = std::numeric_limits<double>::infinity();
    const int rz = dim_ == 3 ? reach : 0;
    for (long k = -rz; k <= rz; ++k)
        for (long j = -reach; j <= reach; ++j)
            for (long i = -reach; i <= reach; ++i) {
                const auto it = cells_.find(key(c[0] + i, c[1] + j, c[2] + k));
                if (it == cells_.end()) continue;
                for (const std::uint32_t q : it->second) best = std::min(best, double((points_[q] - p).squaredNorm()));
            }
    return std::sqrt(best);
}

bool PointGrid::anyWithin(const Vec3& p, double radius) const { return nearest(p, 1) < radius; }

namespace {
using V = TriangleMesh::V;

Vec3 toScalar(const V& v, int dim) { return Vec3(Scalar(v[0]), Scalar(v[1]), dim == 3 ? Scalar(v[2]) : Scalar(0)); }

// The segments of the mesh's section by z = 0 (a vertex on the plane counts as above it), each
// with its triangle's normal in the plane.
struct SectionSegment {
    V a, b, normal;
};
std::vector<SectionSegment> sectionSegments(const TriangleMesh& mesh) {
    std::vector<SectionSegment> segments;
    const auto& x = mesh.vertices();
    for (const auto& t : mesh.triangles()) {
        V ends[2];
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            const V& a = x[t[k]];
            const V& b = x[t[(k + 1) % 3]];
            const bool aAbove = a[2] >= 0, bAbove = b[2] >= 0;
            if (aAbove == bAbove) continue;
            const double s = a[2] / (a[2] - b[2]);
            if (n < 2) ends[n++] = a + s * (b - a);
        }
        const V normal = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
        if (n == 2) segments.push_back({ends[0], ends[1], V(normal[0], normal[1], 0).normalized()});
    }
    return segments;
}
} // namespace

SurfaceSamples poissonDiskSurface(const TriangleMesh& mesh, double r, int dim, std::uint32_t seed) {
    std::mt19937_64 random(seed);
    struct Candidate {
        V point, normal;
    };
    std::vector<Candidate> candidates;
    if (dim == 3) {
        // each triangle's points a + (i ab + j ac)/n, i + j ≤ n, n from its longest edge: no point of
        // it farther than step/√3 from a candidate
        const double step = r / 10;
        const auto& x = mesh.vertices();
        for (const auto& t : mesh.triangles()) {
            const V a = x[t[0]], ab = x[t[1]] - a, ac = x[t[2]] - a;
            const V normal = ab.cross(ac).normalized();
            const double longest = std::max({ab.norm(), ac.norm(), (ac - ab).norm()});
            const long n = std::max(1L, long(std::ceil(longest / step)));
            for (long i = 0; i <= n; ++i)
                for (long j = 0; i + j <= n; ++j)
                    candidates.push_back({a + (double(i) * ab + double(j) * ac) / double(n), normal});
        }
    } else {
        const double step = r / 20;
        for (const auto& [a, b, normal] : sectionSegments(mesh)) {
            const double length = (b - a).norm();
            const long n = std::max(1L, long(std::ceil(length / step)));
            for (long k = 0; k <= n; ++k) candidates.push_back({a + (double(k) / double(n)) * (b - a), normal});
        }
    }
    std::shuffle(candidates.begin(), candidates.end(), random);
    PointGrid kept(r, dim);
    SurfaceSamples samples;
    for (const Candidate& c : candidates) {
        const Vec3 p = toScalar(c.point, dim);
        if (kept.anyWithin(p, r)) continue;
        kept.add(p);
        samples.positions.push_back(p);
        samples.normals.push_back(toScalar(c.normal, dim));
    }
    return samples;
}

namespace {
template <class F> void forLattice(const TriangleMesh& mesh, Scalar dx, int dim, Scalar margin, F&& f) {
    long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) {
        lo[a] = long(std::floor((mesh.boundsMin()[a] - double(margin)) / double(dx))) - 1;
        hi[a] = long(std::ceil((mesh.boundsMax()[a] + double(margin)) / double(dx))) + 1;
    }
    for (long k = lo[2]; k <= hi[2]; ++k)
        for (long j = lo[1]; j <= hi[1]; ++j)
            for (long i = lo[0]; i <= hi[0]; ++i) {
                const Vec3 p((i + Scalar(0.5)) * dx, (j + Scalar(0.5)) * dx, dim == 3 ? (k + Scalar(0.5)) * dx : Scalar(0));
                f(p);
            }
}
} // namespace

std::vector<Vec3> latticeLayers(const TriangleMesh& mesh, Scalar dx, int dim, Scalar thickness, bool outside) {
    std::vector<Vec3> out;
    forLattice(mesh, dx, dim, outside ? thickness : Scalar(0), [&](const Vec3& p) {
        const V q = p.cast<double>();
        if (mesh.inside(q) == outside) return;
        if (mesh.distance(q, double(thickness)) < double(thickness)) out.push_back(p);
    });
    return out;
}

std::vector<Vec3> latticeInside(const TriangleMesh& mesh, Scalar dx, int dim) {
    std::vector<Vec3> out;
    forLattice(mesh, dx, dim, 0, [&](const Vec3& p) {
        if (mesh.inside(p.cast<double>())) out.push_back(p);
    });
    return out;
}

} // namespace spindrift
