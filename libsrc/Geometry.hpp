// Spindrift — constant/geometry: fluid regions, walls and bodies sampled into particles on the
// lattice of spacing Δx.
//
//   fluid { <name> { <shape>; velocity (0 0 0); initialPressure zero; } ... }
//           velocity: each component a number or a quoted expression of x, y, z (Expression.hpp);
//           initialPressure zero | hydrostatic (p = ρ0 |g| depth below its top) | "<expression>"
//   walls { <name> { type container; min (..); max (..); layers 3; open (yMax); }   // hollow box
//           <name> { <shape>; layers 3;                                            // a solid
//                    motion { type linear; velocity (0.5 0 0); } } ... }           // optional (Motion.hpp)
//   bodies { <name> { <shape>; layers 3; density 500; ... } }  // rigid bodies
//           (sampled as solids; their mass, inertia and constraints: RigidBody::read)
//   periodic { x (0 1); }   // optional: axis (min max); leaving at max re-enters at min
//   <shape>: type box | cylinder | sphere | polygon, and optionally subtract { ... } (Shape.hpp)
//
// A shape's particles are its lattice points inside it (Shape.hpp: a box's lattice from its min,
// every other shape's from the origin). A container's wall particles continue the lattice
// outwards: layer k of a face lies (k + ½)Δx outside it, so the effective wall is the face
// itself. A solid keeps the `layers` outermost lattice layers inside its surface. A wall box or
// container whose size is not a whole number of Δx along an axis is refused (the error gives the
// nearest valid max), unless its entry says `snapToLattice yes;`: its max is then moved to
// min + round(size/Δx) Δx (the log says so) and its particles fill it to its faces. Fluid
// particles inside a solid wall or body, or nearer one of its particles than Δx, are removed: on
// a slope or a curve the water fills the lattice up to the wall's particles. Fluid regions are filled in file
// order; a position an earlier region fills is not filled again (OccupiedSpace: overlapping
// regions are merged, a warning per region says how many positions it shared). A hydrostatic
// start takes each particle's depth from the free surface above it, over every fluid region: the
// top of the fluid in its column, down to the first gap of more than half a spacing (a solid wall
// or body under water does not end the column). Each wall
// entry is a wall system of its own, named after the entry; names of walls and blocks are words
// of letters, digits, '_', '-' and '.' starting with a letter or '_' (a wall's name is a file
// name, <name>.vtp, and a ParaView block name in the .pvd).
//   walls { <name> { type mesh; file "tank.obj"; sampling lattice|poissonDisk; layers 3; spacing 0.5;
//                    side inside|outside; scale 1; rotate (0 0 0); translate (0 0 0); } }
//           a mesh from constant/triSurface/ (MeshShape.hpp, SurfaceSampling.hpp); fluid regions and
//           bodies of `type mesh` are Shapes (Shape.hpp).
#pragma once

#include "Dictionary.hpp"
#include "NeighbourSearch.hpp"
#include "Shape.hpp"
#include "Types.hpp"

#include <memory>
#include <string>
#include <vector>

namespace spindrift {

class TriangleMesh;
// A uniform solid body's volume (2D: area), centroid and inertia about it per unit density.
struct BodyMassProperties {
    double volume = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

struct SampledWall {
    std::string name;
    SourceLocation where; // the wall's entry in constant/geometry
    std::vector<Vec3> positions;
    // A single layer on a surface (`sampling poissonDisk`): the surface's unit normal at each
    // particle (either orientation), else empty
    std::vector<Vec3> normals;
    Scalar surfaceSpacing = 0; // its sampling radius
    const Dictionary* motion = nullptr; // the entry's `motion { }`, read by the caller (Motion::read)
    const Dictionary* body = nullptr;   // a `bodies` entry: the whole entry (rigidBodyFrom reads it)
    // A solid wall's or body's shape (none for a container); [min, max] its bounds.
    std::shared_ptr<const Shape> shape;
    BodyMassProperties mass; // a body's, of its shape
    // The space it occupies as sampled: a solid shape, or a container's shell, 'thickness'
    // (its layers) outside [min, max] less the slabs beyond its open faces (xMin xMax yMin ...).
    bool container = false;
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();
    Scalar thickness = 0;
    bool open[6] = {false, false, false, false, false, false};
    // A `type mesh` wall: its surface (placed), and whether it is closed and its solid side is its
    // outside (`side outside`: a hollow vessel holding the fluid) rather than its inside.
    std::shared_ptr<const TriangleMesh> mesh;
    bool meshClosed = false, meshOutside = false;
    // Whether p (shifted back by the wall's displacement d) lies in that space, more than
    // 'margin' inside it.
    bool occupies(const Vec3& p, int dimension, Scalar margin = 0) const;
};

// A fluid block as sampled: its particles are [first, first + count) of the fluid's.
struct SampledBlock {
    std::string name;
    SourceLocation where;
    std::size_t first = 0, count = 0;
    Vec3 min = Vec3::Zero(), max = Vec3::Zero(); // its box
};

struct SampledGeometry {
    std::vector<Vec3> fluidPositions;
    std::vector<Vec3> fluidVelocities;
    // each fluid particle's depth below the free surface above it along gravity (the top of the
    // fluid in its column), where its block starts hydrostatic (initialPressure hydrostatic), else
    // 0: the start gives it p = ρ0 |g| depth
    std::vector<Scalar> fluidDepths;
    // each fluid particle's initial pressure from its region's `initialPressure "<expression>"`, else 0
    std::vector<Scalar> fluidPressures;
    std::vector<SampledBlock> fluidBlocks;
    std::vector<SampledWall> walls;
    Vec3 boundsMin = Vec3::Zero(), boundsMax = Vec3::Zero(); // of everything sampled
    Periodicity periodic;
};

// The space the particles of earlier regions fill, for sampling regions one after another (the
// fluid blocks; regions filled from a mesh later): a candidate nearer than (1 − 10⁻³) Δx to a
// particle of an earlier region is a position already filled, and is not filled again. Only the
// earlier particles near the new region are indexed (the cells of Δx they lie in, sorted), so
// regions that do not touch cost a comparison of boxes.
class OccupiedSpace {
public:
    OccupiedSpace(Scalar spacing, int dimension) : dx_(spacing), dim_(dimension) {}
    // Starts a region within [lo, hi]: the particles placed so far ('placed', every region's
    // before it) are the earlier ones.
    void beginRegion(const std::vector<Vec3>& placed, const Vec3& lo, const Vec3& hi);
    // Ends it: its particles are placed[begin, placed.size()).
    void endRegion(const std::vector<Vec3>& placed);
    bool filled(const Vec3& p) const;

private:
    struct Region {
        Vec3 lo, hi;
        std::size_t begin, end;
    };
    bool cellOf(const Vec3& p, long c[3]) const;
    std::uint64_t key(const long c[3]) const;
    Scalar dx_;
    int dim_;
    std::vector<Region> regions_;
    std::size_t begin_ = 0; // of the current region
    Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
    long cells_[3] = {0, 0, 0};
    const std::vector<Vec3>* placed_ = nullptr;
    std::vector<std::pair<std::uint64_t, std::size_t>> near_; // (cell, particle) sorted: the earlier ones near it
};

// Depth below the free surface above each of 'positions' along 'up' (a unit vector): from the
// top of the particles in its column (cells of Δx across 'up') down to it, plus half a spacing;
// a gap of more than 1.5 Δx between particles of a column starts a new surface below it.
// positions[solidFrom...] are a solid's lattice points: they have no depth of their own and start no
// surface, but bridge a column where water lies above them (the water under a submerged wall is
// as deep as the water above it, whatever the gap between the solid and the water below it).
std::vector<Scalar> depthsBelowFreeSurface(const std::vector<Vec3>& positions, const Vec3& up, Scalar spacing,
                                           int dimension, std::size_t solidFrom = std::size_t(-1));

// How many particles sampleGeometry would make, from the sizes of the blocks and walls alone (no
// sampling, nothing allocated; an upper bound: solids and open faces are not subtracted). A
// spacing far too fine for the domain (or `layers 1e9`) is seen before the memory runs out.
struct ParticleEstimate {
    double count = 0;         // all blocks and walls
    double fluid = 0;         // of which in fluid blocks
    double largest = 0;       // the largest block or wall's share
    std::string largestName;  // e.g. "walls.tank"
    SourceLocation largestAt; // its entry in constant/geometry
};
ParticleEstimate estimateParticleCount(const Dictionary& geometry, Scalar spacing, int dimension);

SampledGeometry sampleGeometry(const Dictionary& geometry, Scalar spacing, int dimension,
                               const Vec3& gravity = Vec3::Zero());

} // namespace spindrift
