// Spindrift — constant/geometry: fluid blocks and walls sampled into particles on the lattice
// of spacing Δx.
//
//   fluid { <name> { type box; min (..); max (..); velocity (0 0 0); } ... }
//   walls { <name> { type container; min (..); max (..); layers 3; open (yMax); }   // hollow box
//           <name> { type box; min (..); max (..); layers 3; } ... }                // solid block
//   periodic { x (0 1); }   // optional: axis (min max); leaving at max re-enters at min
//
// Fluid particles sit at min + (i + ½)Δx. A container's wall particles continue that lattice
// outwards: layer k of a face lies (k + ½)Δx outside it, so the effective wall is the face
// itself. A solid box keeps the `layers` outermost lattice layers inside its surface. Fluid
// particles inside a solid wall are removed. Room for cylinders, spheres and STL later: each
// shape is one `type`.
#pragma once

#include "Dictionary.hpp"
#include "NeighbourSearch.hpp"
#include "Types.hpp"

#include <vector>

namespace spindrift {

struct SampledGeometry {
    std::vector<Vec3> fluidPositions;
    std::vector<Vec3> fluidVelocities;
    std::vector<Vec3> wallPositions;
    Vec3 boundsMin = Vec3::Zero(), boundsMax = Vec3::Zero(); // of everything sampled
    Periodicity periodic;
};

SampledGeometry sampleGeometry(const Dictionary& geometry, Scalar spacing, int dimension);

} // namespace spindrift
