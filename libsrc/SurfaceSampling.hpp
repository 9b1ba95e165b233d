// Spindrift — particles from a triangle mesh (TriangleMesh.hpp): the Poisson-disk single layer on
// its surface (the boundary of seed 002, Duan et al., §3.2, with Akinci's adaptive volume), the
// lattice layers inside or outside it (adami walls) and the lattice points inside it (fluid).
//
// Poisson-disk sampling: dart throwing (Cook 1986; as surveyed by Bridson 2007, "Fast Poisson disk
// sampling in arbitrary dimensions", SIGGRAPH sketches, doi 10.1145/1278780.1278807, which
// Schechter and Bridson 2012 — seed 002's reference [25] — sample their solids with) over a dense
// set of candidates on the surface (on each triangle a regular grid of points r/10 apart, all of
// them in a shuffled order): a candidate is kept when no kept sample lies within r. Every pair of
// samples is at least r apart; every candidate rejected lies within r of a sample, so no point of
// the surface is farther than r + r/(10√3) from one. In 2D the surface is the section of the mesh
// by z = 0 (segments, candidates every r/20 along them).
//
// The lattice is the case's: points (i + ½) Δx along each axis from the origin (a box from 0 to a
// multiple of Δx is filled with exactly the points the `box` primitive gives). A lattice wall keeps
// the points on the solid side of the surface nearer to it than layers·Δx (3D distance; in 2D the
// points of z = 0).
#pragma once

#include "TriangleMesh.hpp"
#include "Types.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace spindrift {

// The samples and the unit normal of the face each lies on (the triangle's; in 2D the section
// segment's, in the plane): the collision with a single layer reads its surface from them
// (WallCollision.hpp).
struct SurfaceSamples {
    std::vector<Vec3> positions, normals;
};
SurfaceSamples poissonDiskSurface(const TriangleMesh& mesh, double radius, int dim, std::uint32_t seed = 2012);

// Lattice points of spacing dx (the case's lattice) within 'thickness' of the surface, inside the
// mesh or (outside = true) outside it. The mesh must be prepared.
std::vector<Vec3> latticeLayers(const TriangleMesh& mesh, Scalar dx, int dim, Scalar thickness, bool outside);
// Lattice points inside the mesh.
std::vector<Vec3> latticeInside(const TriangleMesh& mesh, Scalar dx, int dim);

// The points of a set in cells of a given size: whether one lies nearer than a distance.
class PointGrid {
public:
    PointGrid(double cell, int dim) : cell_(cell), dim_(dim) {}
    void add(const Vec3& p);
    bool anyWithin(const Vec3& p, double radius) const; // radius ≤ cell
    // Distance to the nearest point within 'reach' cells (+∞ if none).
    double nearest(const Vec3& p, int reach = 1) const;
    std::size_t size() const { return points_.size(); }

private:
    std::uint64_t key(long i, long j, long k) const;
    void cellOf(const Vec3& p, long c[3]) const;
    double cell_;
    int dim_;
    std::vector<Vec3> points_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

} // namespace spindrift
