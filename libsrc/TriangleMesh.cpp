#include "TriangleMesh.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace spindrift {

TriangleMesh TriangleMesh::read(const std::filesystem::path& file, const SourceLocation& where,
                                const std::string& keyword) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw InputError(where, "cannot read mesh file '" + file.string() + "': no such file (meshes are read from "
                                "the case's constant/triSurface/)", keyword);
    Assimp::Importer importer;
    // (no aiProcess_JoinIdenticalVertices: STL's per-face normals keep it from joining; welded below)
    const aiScene* scene = importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (!scene || !scene->mRootNode)
        throw InputError(where, "cannot read mesh file '" + file.string() + "': " + importer.GetErrorString(), keyword);
    std::vector<V> vertices;
    std::vector<std::array<int, 3>> triangles;
    std::map<std::array<double, 3>, int> index;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue; // points and lines
            std::array<int, 3> t{};
            for (int k = 0; k < 3; ++k) {
                const aiVector3D& a = mesh->mVertices[face.mIndices[k]];
                const std::array<double, 3> key{double(a.x), double(a.y), double(a.z)};
                const auto [it, added] = index.emplace(key, int(vertices.size()));
                if (added) vertices.emplace_back(key[0], key[1], key[2]);
                t[k] = it->second;
            }
            if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) triangles.push_back(t);
        }
    }
    if (triangles.empty())
        throw InputError(where, "mesh file '" + file.string() + "' has no triangles", keyword);
    return fromTriangles(std::move(vertices), std::move(triangles), file.filename().string());
}

TriangleMesh TriangleMesh::fromTriangles(std::vector<V> vertices, std::vector<std::array<int, 3>> triangles,
                                         std::string name) {
    TriangleMesh m;
    m.name_ = std::move(name);
    m.vertices_ = std::move(vertices);
    m.triangles_ = std::move(triangles);
    m.transform(1, V::Zero(), V::Zero());
    return m;
}

void TriangleMesh::transform(double scale, const V& rotateDegrees, const V& translate) {
    const double k = std::numbers::pi / 180;
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(k * rotateDegrees[2], V::UnitZ()) *
                               Eigen::AngleAxisd(k * rotateDegrees[1], V::UnitY()) *
                               Eigen::AngleAxisd(k * rotateDegrees[0], V::UnitX()))
                                  .toRotationMatrix();
    const bool identity = rotateDegrees == V::Zero();
    lo_ = V::Constant(std::numeric_limits<double>::max());
    hi_ = -lo_;
    for (V& v : vertices_) {
        v = identity ? V(scale * v + translate) : V(R * (scale * v) + translate);
        lo_ = lo_.cwiseMin(v);
        hi_ = hi_.cwiseMax(v);
    }
    if (scale < 0) // a mirror turns the normals inwards: keep the orientation
        for (auto& t : triangles_) std::swap(t[1], t[2]);
    cellStart_.clear();
}

double TriangleMesh::area() const {
    double a = 0;
    for (const auto& t : triangles_)
        a += 0.5 * (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]).norm();
    return a;
}

double TriangleMesh::signedVolume() const {
    double v = 0;
    for (const auto& t : triangles_) v += vertices_[t[0]].dot(vertices_[t[1]].cross(vertices_[t[2]])) / 6;
    return v;
}

namespace {
// directed edge counts: (min, max) → (+1 for a → b with a < b, −1 otherwise, count)
std::map<std::pair<int, int>, std::pair<int, int>> edgeUse(const std::vector<std::array<int, 3>>& triangles) {
    std::map<std::pair<int, int>, std::pair<int, int>> e;
    for (const auto& t : triangles)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            auto& u = e[{std::min(a, b), std::max(a, b)}];
            u.first += a < b ? 1 : -1;
            u.second += 1;
        }
    return e;
}
} // namespace

std::size_t TriangleMesh::openEdges() const {
    std::size_t n = 0;
    for (const auto& [edge, use] : edgeUse(triangles_))
        if (use.second != 2) ++n;
    return n;
}

std::size_t TriangleMesh::inconsistentEdges() const {
    std::size_t n = 0;
    for (const auto& [edge, use] : edgeUse(triangles_))
        if (use.second == 2 && use.first != 0) ++n;
    return n;
}

namespace {
// triangles per cell (CSR) of a grid of n cells 'cell' wide from 'lo', by their bounding boxes
void binTriangles(const std::vector<TriangleMesh::V>& x, const std::vector<std::array<int, 3>>& triangles,
                  const TriangleMesh::V& lo, double cell, const long n[3], double pad,
                  std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& list) {
    const std::size_t cells = std::size_t(n[0]) * n[1] * n[2];
    std::vector<std::uint32_t> count(cells + 1, 0), fill;
    const auto range = [&](std::size_t t, long a[3], long b[3]) {
        TriangleMesh::V l = x[triangles[t][0]], h = l;
        for (int k = 1; k < 3; ++k) {
            l = l.cwiseMin(x[triangles[t][k]]);
            h = h.cwiseMax(x[triangles[t][k]]);
        }
        for (int d = 0; d < 3; ++d) {
            a[d] = std::clamp(long(std::floor((l[d] - pad - lo[d]) / cell)), 0L, n[d] - 1);
            b[d] = std::clamp(long(std::floor((h[d] + pad - lo[d]) / cell)), 0L, n[d] - 1);
        }
    };
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
            start = count;
            list.assign(count[cells], 0);
            fill.assign(start.begin(), start.end() - 1);
        }
        for (std::size_t t = 0; t < triangles.size(); ++t) {
            long a[3], b[3];
            range(t, a, b);
            for (long k = a[2]; k <= b[2]; ++k)
                for (long j = a[1]; j <= b[1]; ++j)
                    for (long i = a[0]; i <= b[0]; ++i) {
                        const std::size_t c = (std::size_t(k) * n[1] + j) * n[0] + i;
                        if (pass == 0) ++count[c + 1];
                        else list[fill[c]++] = std::uint32_t(t);
                    }
        }
    }
}
} // namespace

void TriangleMesh::prepare() {
    const V size = hi_ - lo_;
    const double extent = std::max(size.maxCoeff(), 1e-12);
    const double pad = 1e-9 * extent;
    // distances: about 4 triangles a cell on a surface, at most 128 cells along an axis
    const double perAxis = std::clamp(std::sqrt(double(triangles_.size()) / 4), 4.0, 128.0);
    cell_ = extent / perAxis;
    gridLo_ = lo_ - V::Constant(0.5 * cell_);
    for (int a = 0; a < 3; ++a) n_[a] = std::max(1L, long(std::ceil((size[a] + cell_) / cell_)));
    binTriangles(vertices_, triangles_, gridLo_, cell_, n_, pad, cellStart_, cellTriangles_);
    // winding: coarser
    wcell_ = extent / std::min(perAxis, 32.0);
    wlo_ = lo_ - V::Constant(0.5 * wcell_);
    for (int a = 0; a < 3; ++a) wn_[a] = std::max(1L, long(std::ceil((size[a] + wcell_) / wcell_)));
    binTriangles(vertices_, triangles_, wlo_, wcell_, wn_, pad, wStart_, wTriangles_);
    wFar_.assign(wStart_.size() - 1, std::numeric_limits<double>::quiet_NaN());
    stamp_.assign(triangles_.size(), 0);
    stampValue_ = 0;
}

double TriangleMesh::exactWinding(const V& p) const {
    // Van Oosterom & Strackee: tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|)
    double w = 0;
    for (const auto& t : triangles_) {
        const V a = vertices_[t[0]] - p, b = vertices_[t[1]] - p, c = vertices_[t[2]] - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double det = a.dot(b.cross(c));
        const double div = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        w += 2 * std::atan2(det, div);
    }
    return w / (4 * std::numbers::pi);
}

bool TriangleMesh::cellOf(const V& p, long c[3]) const {
    for (int a = 0; a < 3; ++a) {
        const double s = (p[a] - gridLo_[a]) / cell_;
        if (!(s >= 0 && s < double(n_[a]))) return false;
        c[a] = long(s);
    }
    return true;
}

// The solid angles of the triangles listed within two winding cells of cell c, at p (÷ 4π).
double TriangleMesh::nearWinding(const V& p, const long c[3]) const {
    if (++stampValue_ == 0) {
        std::fill(stamp_.begin(), stamp_.end(), 0);
        stampValue_ = 1;
    }
    double w = 0;
    for (long k = std::max(0L, c[2] - 2); k <= std::min(wn_[2] - 1, c[2] + 2); ++k)
        for (long j = std::max(0L, c[1] - 2); j <= std::min(wn_[1] - 1, c[1] + 2); ++j)
            for (long i = std::max(0L, c[0] - 2); i <= std::min(wn_[0] - 1, c[0] + 2); ++i) {
                const std::size_t cell = (std::size_t(k) * wn_[1] + j) * wn_[0] + i;
                for (std::uint32_t q = wStart_[cell]; q < wStart_[cell + 1]; ++q) {
                    const std::uint32_t t = wTriangles_[q];
                    if (stamp_[t] == stampValue_) continue;
                    stamp_[t] = stampValue_;
                    const V a = vertices_[triangles_[t][0]] - p, b = vertices_[triangles_[t][1]] - p,
                            cc = vertices_[triangles_[t][2]] - p;
                    const double la = a.norm(), lb = b.norm(), lc = cc.norm();
                    w += 2 * std::atan2(a.dot(b.cross(cc)), la * lb * lc + a.dot(b) * lc + b.dot(cc) * la + cc.dot(a) * lb);
                }
            }
    return w / (4 * std::numbers::pi);
}

double TriangleMesh::windingNumber(const V& p) const {
    for (int a = 0; a < 3; ++a)
        if (p[a] < lo_[a] || p[a] > hi_[a]) return 0; // outside the box of a closed mesh (and nearly so of an open one)
    if (wStart_.empty()) return exactWinding(p);
    // The triangles within two winding cells exactly, the rest's part taken at the winding cell's
    // centre (exact where no triangle is that near) (it changes by less than ~0.25 across the cell: a plane beyond two
    // cells subtends a solid angle that moves by at most 2π·(½√3)/2 over it); a sum within 0.3
    // of ½ is recomputed in full.
    long w[3];
    for (int a = 0; a < 3; ++a) {
        const double s = (p[a] - wlo_[a]) / wcell_;
        if (!(s >= 0 && s < double(wn_[a]))) return exactWinding(p);
        w[a] = long(s);
    }
    const std::size_t i = (std::size_t(w[2]) * wn_[1] + w[1]) * wn_[0] + w[0];
    if (std::isnan(wFar_[i])) {
        const V centre = wlo_ + wcell_ * V(w[0] + 0.5, w[1] + 0.5, w[2] + 0.5);
        wFar_[i] = exactWinding(centre) - nearWinding(centre, w);
    }
    const double approx = wFar_[i] + nearWinding(p, w);
    if (std::abs(approx - 0.5) < 0.3) return exactWinding(p);
    return approx;
}

TriangleMesh::V TriangleMesh::closestOnTriangle(const V& p, std::size_t t) const {
    // Ericson, Real-Time Collision Detection (2005), §5.1.5
    const V& a = vertices_[triangles_[t][0]];
    const V& b = vertices_[triangles_[t][1]];
    const V& c = vertices_[triangles_[t][2]];
    const V ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const V bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const V cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

double TriangleMesh::distance(const V& p, double maxDistance) const {
    double best = std::numeric_limits<double>::infinity();
    if (cellStart_.empty()) {
        for (std::size_t t = 0; t < triangles_.size(); ++t) best = std::min(best, (closestOnTriangle(p, t) - p).norm());
        return best <= maxDistance ? best : std::numeric_limits<double>::infinity();
    }
    long lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = long(std::floor((p[a] - maxDistance - gridLo_[a]) / cell_));
        hi[a] = long(std::floor((p[a] + maxDistance - gridLo_[a]) / cell_));
        if (hi[a] < 0 || lo[a] >= n_[a]) return best;
        lo[a] = std::max(lo[a], 0L);
        hi[a] = std::min(hi[a], n_[a] - 1);
    }
    if (++stampValue_ == 0) {
        std::fill(stamp_.begin(), stamp_.end(), 0);
        stampValue_ = 1;
    }
    for (long k = lo[2]; k <= hi[2]; ++k)
        for (long j = lo[1]; j <= hi[1]; ++j)
            for (long i = lo[0]; i <= hi[0]; ++i) {
                const std::size_t c = cellIndex(i, j, k);
                for (std::uint32_t q = cellStart_[c]; q < cellStart_[c + 1]; ++q) {
                    const std::uint32_t t = cellTriangles_[q];
                    if (stamp_[t] == stampValue_) continue;
                    stamp_[t] = stampValue_;
                    best = std::min(best, (closestOnTriangle(p, t) - p).norm());
                }
            }
    return best <= maxDistance ? best : std::numeric_limits<double>::infinity();
}

} // namespace spindrift
