// Spindrift — `type mesh;` in constant/geometry: a triangle mesh (TriangleMesh.hpp) read from the
// case's constant/triSurface/, and the Shape (Shape.hpp) it is as a fluid region, a body or a
// shape cut out of another: inside by the generalised winding number (Jacobson et al. 2013,
// doi 10.1145/2461912.2461916), its signed distance the distance to the nearest triangle
// (exact up to a cap of a few spacings beyond the layers the entry asks for; a bound beyond it).
// Walls of `type mesh` are sampled by Geometry.cpp itself (Poisson-disk or lattice layers, on
// either side: SurfaceSampling.hpp).
#pragma once

#include "Dictionary.hpp"
#include "Shape.hpp"
#include "TriangleMesh.hpp"

#include <memory>

namespace spindrift {

// The entry's mesh (`file`, `scale`, `rotate`, `translate`), checked: a closed one consistently
// oriented with its normals outwards; 'needClosed' refuses an open one ('why' says what needs it).
std::shared_ptr<TriangleMesh> readMesh(const Dictionary& entry, bool needClosed, const char* why);

// The Shape of a `type mesh` entry (a closed mesh; in 2D its section by z = 0).
std::unique_ptr<Shape> readMeshShape(const Dictionary& entry, int dimension, Scalar dx);

} // namespace spindrift
