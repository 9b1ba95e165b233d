// Spindrift — constant/geometry: fluid blocks and walls sampled into particles on the lattice
// of spacing Δx.
//
//   fluid { <name> { type box; min (..); max (..); velocity (0 0 0); initialPressure zero; } ... }
//           initialPressure hydrostatic: the block starts at p = ρ0 |g| (depth below its top)
//   walls { <name> { type container; min (..); max (..); layers 3; open (yMax); }   // hollow box
//           <name> { type box; min (..); max (..); layers 3;                        // solid block
//                    motion { type linear; velocity (0.5 0 0); } } ... }           // optional (Motion.hpp)
//   bodies { <name> { type box; min (..); max (..); layers 3; density 500; ... } }  // rigid bodies
//           (sampled as solid blocks; their mass, inertia and constraints: RigidBodySetUp.hpp)
//   periodic { x (0 1); }   // optional: axis (min max); leaving at max re-enters at min
//
// Fluid particles sit at min + (i + ½)Δx. A container's wall particles continue that lattice
// outwards: layer k of a face lies (k + ½)Δx outside it, so the effective wall is the face
// itself. A solid box keeps the `layers` outermost lattice layers inside its surface. Fluid
// particles inside a solid wall are removed. Each wall entry is a wall system of its own, named
// after the entry. Room for cylinders, spheres and STL later: each shape is one `type`.
#pragma once

#include "Dictionary.hpp"
#include "NeighbourSearch.hpp"
#include "Types.hpp"

#include <string>
#include <vector>

namespace spindrift {

struct SampledWall {
    std::string name;
    std::vector<Vec3> positions;
    const Dictionary* motion = nullptr; // the entry's `motion { }`, read by the caller (Motion::read)
    const Dictionary* body = nullptr;   // a `bodies` entry: the whole entry (rigidBodyFrom reads it)
    Vec3 boxMin = Vec3::Zero(), boxMax = Vec3::Zero(); // the entry's box
};

struct SampledGeometry {
    std::vector<Vec3> fluidPositions;
    std::vector<Vec3> fluidVelocities;
    // each fluid particle's depth below the top of its block along gravity, where the block starts
    // hydrostatic (initialPressure hydrostatic), else 0: the start gives it p = ρ0 |g| depth
    std::vector<Scalar> fluidDepths;
    std::vector<SampledWall> walls;
    Vec3 boundsMin = Vec3::Zero(), boundsMax = Vec3::Zero(); // of everything sampled
    Periodicity periodic;
};

// How many particles sampleGeometry would make, from the sizes of the blocks and walls alone (no
// sampling, nothing allocated; an upper bound: solids and open faces are not subtracted). A
// spacing far too fine for the domain (or `layers 1e9`) is seen before the memory runs out.
struct ParticleEstimate {
    double count = 0;         // all blocks and walls
    double largest = 0;       // the largest block or wall's share
    std::string largestName;  // e.g. "walls.tank"
    SourceLocation largestAt; // its entry in constant/geometry
};
ParticleEstimate estimateParticleCount(const Dictionary& geometry, Scalar spacing, int dimension);

SampledGeometry sampleGeometry(const Dictionary& geometry, Scalar spacing, int dimension,
                               const Vec3& gravity = Vec3::Zero());

} // namespace spindrift
