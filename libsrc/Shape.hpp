// Spindrift — the shapes of constant/geometry: fluid regions, solid walls and rigid bodies are
// each one Shape, read by readShape() from an entry's `type`:
//
//   type box;       min (x y z); max (x y z);
//   type cylinder;  2D: centre (x y 0); radius r;            (a circle)
//                   3D: point1 (..); point2 (..); radius r;  (the axis' end points; flat caps)
//   type sphere;    centre (x y z); radius r;                (2D: a circle)
//   type polygon;   points ((x0 y0 0) (x1 y1 0) ...);        (2D only: a closed simple polygon,
//                                                             either orientation, the last point
//                                                             joined to the first)
//   subtract { <name> { type ...; } ... }   // optional in any entry: these shapes cut out of it
//
// Signed distances: the cylinder (with caps), the sphere, the box and the polygon are exact
// Euclidean distances (Quilez's primitives, e.g. https://iquilezles.org/articles/distfunctions/;
// the polygon: the distance to its nearest edge, signed by the winding number of Hormann &
// Agathos 2001, "The point in polygon problem for arbitrary polygons", Comput. Geom. 20:131–144,
// doi:10.1016/S0925-7721(01)00012-8). A subtraction A − B is max(d_A, −d_B) (a bound, exact
// inside).
//
// Sampling is written once against the interface (Geometry.cpp): a shape's particles are the
// points of its lattice (latticeOrigin + (i + ½)Δx) that lie inside it; a solid's are those
// less than `layers` Δx deep. A box's lattice starts at its min (as ever); every other shape's
// at the case origin, so a shape lines up with every box whose min is a multiple of Δx.
// The mesh helper plugs `type mesh;` into readShape (Shape.cpp) as one more branch.
#pragma once

#include "Dictionary.hpp"
#include "Types.hpp"

#include <memory>
#include <string>

namespace spindrift {

class Shape {
public:
    virtual ~Shape() = default;
    // < 0 inside, > 0 outside, its magnitude the distance to the surface (or a lower bound of it
    // outside a subtraction); in 2D z is ignored
    virtual Scalar signedDistance(const Vec3& p) const = 0;
    // The box [lo, hi] that holds it (2D: z of both 0).
    virtual void bounds(Vec3& lo, Vec3& hi) const = 0;
    // e.g. "cylinder centre (0 0 0) radius 1"
    virtual std::string describe() const = 0;
    // Whether p lies in the shape grown by 'margin' (shrunk where negative). A box grows as a box
    // (its corners square, as the sampling of boxes always did); the rest by signed distance.
    virtual bool contains(const Vec3& p, Scalar margin = 0) const { return signedDistance(p) < margin; }
    // Its sampling lattice: origin + (i + ½)Δx, cells[a] cells along each axis from the origin.
    virtual void lattice(Scalar dx, Vec3& origin, long cells[3]) const;
    // Whether it is an axis-aligned box (and nothing cut out of it): its particles then fill it
    // face to face, and a rigid body's mass comes from its box.
    virtual bool isBox() const { return false; }
    int dimension() const { return dim_; }

protected:
    explicit Shape(int dimension) : dim_(dimension) {}
    int dim_;
};

// The shape of a constant/geometry entry (fluid region, wall or body), from its `type` among
// 'allowed' (an empty list: every type). Errors name the entry's file, line and keyword.
std::unique_ptr<Shape> readShape(const Dictionary& entry, int dimension, Scalar dx,
                                 const std::vector<std::string>& allowed = {});

// An axis-aligned box [lo, hi] (what `type box;` reads).
std::unique_ptr<Shape> makeBox(const Vec3& lo, const Vec3& hi, int dimension);

// Every type readShape knows (for messages): box cylinder sphere polygon ...
const std::vector<std::string>& shapeTypes();

// Calls f(p) for each point of the shape's lattice, inside or not (a lattice of ~1e15 points
// or more is the caller's to refuse first).
template <class F> void forEachLatticePoint(const Shape& s, Scalar dx, F&& f) {
    Vec3 o;
    long n[3];
    s.lattice(dx, o, n);
    const int dim = s.dimension();
    for (long k = 0; k < n[2]; ++k)
        for (long j = 0; j < n[1]; ++j)
            for (long i = 0; i < n[0]; ++i)
                f(Vec3(o[0] + (i + Scalar(0.5)) * dx, o[1] + (j + Scalar(0.5)) * dx,
                       dim == 3 ? o[2] + (k + Scalar(0.5)) * dx : Scalar(0)));
}

// The lattice points of a shape: all inside it (thickness ≤ 0), or those less than 'thickness'
// deep (a solid wall's outermost layers), appended to 'out'.
void sampleShape(const Shape& s, Scalar dx, Scalar thickness, std::vector<Vec3>& out);

// How many lattice points the shape's lattice has (an upper bound of its particles), in double.
double latticePointCount(const Shape& s, Scalar dx);

} // namespace spindrift
