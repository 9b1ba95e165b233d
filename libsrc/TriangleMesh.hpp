// Spindrift — triangle meshes for constant/geometry (`type mesh; file "name.stl";`): read from a
// case's constant/triSurface/ (STL ASCII and binary, OBJ, any format Assimp reads), placed by
// `scale`, `rotate`, `translate`, checked, and queried for inside/outside and distance.
//
// Inside/outside: the generalised winding number w(p) = Σ_t Ω_t(p) / 4π (Jacobson, Kavan and
// Sorkine-Hornung 2013, "Robust inside-outside segmentation using generalized winding numbers",
// ACM TOG 32(4), doi 10.1145/2461912.2461916, eq. 2 with the solid angle of a triangle by
// Van Oosterom and Strackee 1983, eq. 8), p inside where w > ½. It is exact (±1, 0) for a closed,
// consistently oriented mesh and does not care about a point lying on an edge or a vertex of the
// triangulation. Speed: a grid of cells (at most 32 an axis) lists the triangles whose bounding
// boxes meet each cell; w(p) is the exact sum over the triangles listed within two cells of p's
// cell plus the rest's part, taken once at the cell's centre (it varies by less than ~0.25 over
// the cell); a result within 0.3 of ½ is recomputed in full. Inside is decided exactly; the value
// returned is within ~0.25 of w.
// Distances to the surface use a finer grid of the same kind (closest point on a triangle:
// Ericson 2005, §5.1.5).
#pragma once

#include "Error.hpp"
#include "Types.hpp"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace spindrift {

class TriangleMesh {
public:
    using V = Eigen::Vector3d; // the mesh works in double whatever Scalar is

    // Reads 'file' with Assimp (vertices welded where their positions are equal). Errors name the
    // file and 'where' (the entry's `file` keyword): unreadable, no triangles.
    static TriangleMesh read(const std::filesystem::path& file, const SourceLocation& where,
                             const std::string& keyword = "file");
    static TriangleMesh fromTriangles(std::vector<V> vertices, std::vector<std::array<int, 3>> triangles,
                                      std::string name = "<mesh>");

    // x → R (s x) + t, R = Rz(γ) Ry(β) Rx(α) for rotate (α β γ) in degrees.
    void transform(double scale, const V& rotateDegrees, const V& translate);

    const std::string& name() const { return name_; }
    const std::vector<V>& vertices() const { return vertices_; }
    const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
    V boundsMin() const { return lo_; }
    V boundsMax() const { return hi_; }
    double area() const;
    // Σ a·(b × c)/6: the enclosed volume of a closed mesh, negative when its normals point inwards.
    double signedVolume() const;
    // Edges not shared by exactly two triangles, or shared by two of the same orientation.
    std::size_t openEdges() const;
    std::size_t inconsistentEdges() const;

    // Builds the search grid (after the last transform; the queries need it).
    void prepare();
    double windingNumber(const V& p) const;
    bool inside(const V& p) const { return windingNumber(p) > 0.5; }
    // Distance from p to the surface, or +∞ when it is farther than 'maxDistance'.
    double distance(const V& p, double maxDistance) const;
    // The closest point on triangle t to p.
    V closestOnTriangle(const V& p, std::size_t t) const;

private:
    double exactWinding(const V& p) const;
    bool cellOf(const V& p, long c[3]) const;
    std::size_t cellIndex(long i, long j, long k) const { return (std::size_t(k) * n_[1] + j) * n_[0] + i; }

    std::string name_;
    std::vector<V> vertices_;
    std::vector<std::array<int, 3>> triangles_;
    V lo_ = V::Zero(), hi_ = V::Zero();
    // grid
    V gridLo_ = V::Zero();
    double cell_ = 1;
    long n_[3] = {0, 0, 0};
    std::vector<std::uint32_t> cellStart_; // CSR: triangles of cell c are cellTriangles_[cellStart_[c], cellStart_[c+1])
    std::vector<std::uint32_t> cellTriangles_;
    // the winding grid: coarser cells (at most 32 an axis); a cell's far part (every triangle not
    // listed within two cells of it) at its centre, NaN until computed
    double wcell_ = 1;
    V wlo_ = V::Zero();
    long wn_[3] = {0, 0, 0};
    std::vector<std::uint32_t> wStart_, wTriangles_;
    mutable std::vector<double> wFar_;
    double nearWinding(const V& p, const long c[3]) const;
    mutable std::vector<std::uint32_t> stamp_;
    mutable std::uint32_t stampValue_ = 0;
};

} // namespace spindrift
