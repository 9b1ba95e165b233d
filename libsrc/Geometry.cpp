#include "Geometry.hpp"

#include "Expression.hpp"
#include "Log.hpp"
#include "MeshShape.hpp"
#include "SurfaceSampling.hpp"
#include "TriangleMesh.hpp"
#include "Shape.hpp"

#include <Eigen/Geometry> // cross, unitOrthogonal

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <sstream>

namespace spindrift {
namespace {

struct Box {
    Vec3 min, max;
    bool contains(const Vec3& p, int dim, Scalar tol = 0) const {
        for (int a = 0; a < dim; ++a)
            if (p[a] < min[a] - tol || p[a] > max[a] + tol) return false;
        return true;
    }
};

Box readBox(const Dictionary& d, int dim) {
    Box b{d.get<Vec3>("min"), d.get<Vec3>("max")};
    for (int a = 0; a < dim; ++a)
        if (!(b.max[a] > b.min[a])) {
            std::ostringstream s;
            s << "'max' must exceed 'min' in every direction (axis " << "xyz"[a] << ": min " << b.min[a]
              << ", max " << b.max[a] << ") in " << d.name();
            throw InputError(d.locationOf("max"), s.str(), "max");
        }
    if (dim == 2) b.min[2] = b.max[2] = 0;
    return b;
}

// Lattice of cell centres lo + (i + ½)Δx covering [lo, hi] (n = round((hi - lo)/Δx) cells per axis).
template <class F> void forEachLatticePoint(const Vec3& lo, const Vec3& hi, Scalar dx, int dim, F&& f) {
    long n[3] = {1, 1, 1};
    for (int a = 0; a < dim; ++a) n[a] = std::max(0L, std::lround((hi[a] - lo[a]) / dx));
    for (long k = 0; k < n[2]; ++k)
        for (long j = 0; j < n[1]; ++j)
            for (long i = 0; i < n[0]; ++i) {
                Vec3 p(lo[0] + (i + Scalar(0.5)) * dx, lo[1] + (j + Scalar(0.5)) * dx,
                       dim == 3 ? lo[2] + (k + Scalar(0.5)) * dx : Scalar(0));
                f(p);
            }
}

// A wall's or block's name: it names a file (<wall>.vtp) and a block of the .pvd (XML), so letters,
// digits, '_', '-' and '.', starting with a letter or '_' (a word of OpenFOAM's that needs no
// quoting or escaping anywhere), at most 128 characters.
void checkName(const Dictionary& parent, const std::string& name, const char* what) {
    const auto allowed = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    };
    const bool valid = !name.empty() && name.size() <= 128 &&
                       (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                       std::all_of(name.begin(), name.end(), allowed);
    if (!valid)
        throw InputError(parent.locationOf(name),
                         std::string(what) + " name '" + name +
                             "' is not a plain word: use letters, digits, '_', '-' and '.', starting with a letter "
                             "or '_' (at most 128 characters; it names " +
                             (std::string(what) == "wall" ? "the file " + name + ".vtp and its block in the .pvd)"
                                                          : "the block in messages)"),
                         name);
}

// A box (a wall, a container's inside, a fluid block, a body) must be a whole number of spacings
// along each axis for the lattice to fill it face to face: a fluid block of 27.5 spacings would
// hold 28 rows of water, a body's particles would not cover its mass. One that is not is refused
// (its entry, `max`, the nearest valid max values), unless the entry says `snapToLattice yes;`:
// then its max is moved to min + round(size/Δx) Δx, which the log says. `what` names it ("wall").
void snapToLattice(Box& box, const Dictionary& entry, const std::string& scopedName, Scalar dx, int dim,
                   const char* what) {
    const bool snap = entry.getOrDefault<bool>("snapToLattice", false);
    for (int a = 0; a < dim; ++a) {
        const Scalar cells = std::round((box.max[a] - box.min[a]) / dx);
        // (the tolerance allows for the rounding of a float build as well)
        const Scalar tolerance = std::max(Scalar(1e-6) * dx, 64 * std::numeric_limits<Scalar>::epsilon() *
                                                                 (std::abs(box.min[a]) + std::abs(box.max[a])));
        if (std::abs(cells * dx - (box.max[a] - box.min[a])) > tolerance) {
            std::ostringstream s;
            s << scopedName << ": size along " << "xyz"[a] << " (" << box.max[a] - box.min[a]
              << ") is not a multiple of particleSpacing " << dx;
            if (!snap) {
                const Scalar below = std::floor((box.max[a] - box.min[a]) / dx);
                s << "; the nearest valid max " << "xyz"[a] << " are " << box.min[a] + std::max(Scalar(1), below) * dx
                  << " and " << box.min[a] + (std::max(Scalar(1), below) + 1) * dx
                  << " (or add 'snapToLattice yes;' to the entry to place it at " << box.min[a] + std::max(Scalar(1), cells) * dx
                  << ")";
                throw InputError(entry.locationOf("max"), s.str(), "max");
            }
            s << "; the " << what << " is placed at max " << "xyz"[a] << " = " << box.min[a] + cells * dx << " (snapToLattice)";
            log::info(locatedMessage(entry.locationOf("max"), "", s.str()));
            box.max[a] = box.min[a] + cells * dx;
        }
    }
}

// An entry's shape; a box made a whole number of spacings (or refused: snapToLattice).
std::unique_ptr<Shape> snappedShape(const Dictionary& entry, const std::string& scopedName, Scalar dx, int dim,
                                    const char* what) {
    std::unique_ptr<Shape> shape = readShape(entry, dim, dx);
    if (!shape->isBox()) return shape;
    Box box;
    shape->bounds(box.min, box.max);
    snapToLattice(box, entry, scopedName, dx, dim, what);
    return makeBox(box.min, box.max, dim);
}

const std::vector<std::string>& wallTypes() {
    static const std::vector<std::string> types = [] {
        std::vector<std::string> t{"container"};
        t.insert(t.end(), shapeTypes().begin(), shapeTypes().end());
        return t;
    }();
    return types;
}

// A uniform solid's volume, centroid and inertia per unit density: a box's exactly (as ever),
// any other shape's from its lattice points inside it, each Δx^dim of it (a point mass each; the
// lattice's own error, O(Δx/size), is that of its particles).
BodyMassProperties massProperties(const Shape& shape, Scalar dx) {
    BodyMassProperties m;
    const int dim = shape.dimension();
    Vec3 lo, hi;
    shape.bounds(lo, hi);
    if (shape.isBox()) {
        const Eigen::Vector3d size = (hi - lo).cast<double>();
        m.volume = dim == 2 ? size[0] * size[1] : size[0] * size[1] * size[2];
        m.centroid = 0.5 * (lo + hi).cast<double>();
        if (dim == 2) m.centroid[2] = 0;
        // the uniform box about its centre: I_xx = V (b² + c²)/12, ... (2D: the in-plane Izz)
        m.inertia = Eigen::Matrix3d::Zero();
        m.inertia(0, 0) = m.volume * (size[1] * size[1] + size[2] * size[2]) / 12;
        m.inertia(1, 1) = m.volume * (size[0] * size[0] + size[2] * size[2]) / 12;
        m.inertia(2, 2) = m.volume * (size[0] * size[0] + size[1] * size[1]) / 12;
        return m;
    }
    std::vector<Vec3> points;
    sampleShape(shape, dx, 0, points);
    const double cell = dim == 2 ? double(dx) * double(dx) : double(dx) * double(dx) * double(dx);
    m.volume = double(points.size()) * cell;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const Vec3& p : points) c += p.cast<double>();
    if (!points.empty()) c /= double(points.size());
    m.centroid = c;
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    for (const Vec3& p : points) {
        const Eigen::Vector3d r = p.cast<double>() - c;
        I += cell * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    if (dim == 2) { // a lamina per unit depth: only Izz = ∫ (x² + y²) matters
        I(0, 1) = I(1, 0) = I(0, 2) = I(2, 0) = I(1, 2) = I(2, 1) = 0;
    }
    m.inertia = I;
    return m;
}

// A fluid region's initial velocity: `velocity (u v w);`, each component a number or a quoted
// expression of x, y, z (Expression.hpp).
struct VelocityField {
    Vec3 constant = Vec3::Zero();
    std::unique_ptr<Expression> component[3];
    Vec3 at(const Vec3& p, int dim) const {
        Vec3 v = constant;
        for (int a = 0; a < 3; ++a)
            if (component[a]) v[a] = Scalar((*component[a])(p));
        if (dim == 2) v[2] = 0;
        return v;
    }
};

VelocityField readVelocity(const Dictionary& f, int dim) {
    VelocityField field;
    const Entry* e = f.findEntry("velocity");
    const bool expressions =
        e && !e->isDict() && std::any_of(e->tokens.begin(), e->tokens.end(), [](const Token& t) {
            return t.kind == Token::Kind::String;
        });
    if (!expressions) {
        field.constant = f.getOrDefault<Vec3>("velocity", Vec3::Zero());
        if (dim == 2) field.constant[2] = 0;
        return field;
    }
    f.markUsed("velocity");
    const auto& t = e->tokens;
    const bool shaped = t.size() == 5 && t.front().kind == Token::Kind::Open && t.back().kind == Token::Kind::Close;
    for (std::size_t k = 1; shaped && k < 4; ++k) {
        if (t[k].kind == Token::Kind::String) {
            field.component[k - 1] = std::make_unique<Expression>(t[k].text, t[k].where, "velocity");
        } else if (t[k].kind == Token::Kind::Number) {
            field.constant[k - 1] = Scalar(std::stod(t[k].text));
        } else {
            throw InputError(t[k].where, "a component of 'velocity' must be a number or a quoted expression of x, y, "
                             "z, e.g. velocity (\"-100*x\" \"100*y\" 0); found '" + t[k].text + "'", "velocity");
        }
    }
    if (!shaped)
        throw InputError(f.locationOf("velocity"), "'velocity' needs 3 components, each a number or a quoted "
                         "expression of x, y, z, e.g. velocity (\"-100*x\" \"100*y\" 0);", "velocity");
    return field;
}

int faceIndex(const std::string& face) {
    static const char* names[6] = {"xMin", "xMax", "yMin", "yMax", "zMin", "zMax"};
    for (int i = 0; i < 6; ++i)
        if (face == names[i]) return i;
    return -1;
}

} // namespace

bool SampledWall::occupies(const Vec3& p, int dim, Scalar margin) const {
    if (mesh) {
        const TriangleMesh::V q = p.cast<double>();
        const double d = mesh->distance(q, double(thickness));
        if (!meshClosed) return d < double(thickness - margin);
        return mesh->inside(q) != meshOutside && d >= double(margin) && d < double(thickness);
    }
    if (!container) {
        if (shape) return shape->contains(p, -margin);
        return Box{min, max}.contains(p, dim, -margin);
    }
    // the shell: within 'thickness' outside the inner box, not inside it, not beyond an open face
    if (!Box{min - Vec3::Constant(thickness), max + Vec3::Constant(thickness)}.contains(p, dim, -margin)) return false;
    bool inShell = false;
    for (int a = 0; a < dim; ++a) {
        if (p[a] < min[a] - margin) {
            if (open[2 * a]) return false;
            inShell = true;
        }
        if (p[a] > max[a] + margin) {
            if (open[2 * a + 1]) return false;
            inShell = true;
        }
    }
    return inShell;
}

void OccupiedSpace::beginRegion(const std::vector<Vec3>& placed, const Vec3& lo, const Vec3& hi) {
    placed_ = &placed;
    begin_ = placed.size();
    lo_ = lo - Vec3::Constant(2 * dx_);
    hi_ = hi + Vec3::Constant(2 * dx_);
    for (int a = 0; a < 3; ++a) {
        const double n = std::ceil(double(hi_[a] - lo_[a]) / double(dx_)) + 1; // (a box of any size)
        cells_[a] = a >= dim_ ? 1 : n < 1e15 ? long(n) : long(1e15);
    }
    near_.clear();
    for (const Region& r : regions_) {
        bool touches = true;
        for (int a = 0; a < dim_; ++a) touches = touches && r.lo[a] <= hi_[a] && r.hi[a] >= lo_[a];
        if (!touches) continue;
        long c[3];
        for (std::size_t k = r.begin; k < r.end; ++k)
            if (cellOf(placed[k], c)) near_.emplace_back(key(c), k);
    }
    std::sort(near_.begin(), near_.end());
}

void OccupiedSpace::endRegion(const std::vector<Vec3>& placed) {
    if (placed.size() == begin_) return;
    Vec3 lo = placed[begin_], hi = lo;
    for (std::size_t k = begin_; k < placed.size(); ++k) {
        lo = lo.cwiseMin(placed[k]);
        hi = hi.cwiseMax(placed[k]);
    }
    regions_.push_back({lo, hi, begin_, placed.size()});
}

bool OccupiedSpace::cellOf(const Vec3& p, long c[3]) const {
    for (int a = 0; a < 3; ++a) {
        if (a >= dim_) {
            c[a] = 0;
            continue;
        }
        const Scalar s = (p[a] - lo_[a]) / dx_;
        if (!(s >= 0 && s < Scalar(cells_[a]))) return false;
        c[a] = long(s);
    }
    return true;
}

std::uint64_t OccupiedSpace::key(const long c[3]) const {
    return (std::uint64_t(c[2]) * std::uint64_t(cells_[1]) + std::uint64_t(c[1])) * std::uint64_t(cells_[0]) +
           std::uint64_t(c[0]);
}

bool OccupiedSpace::filled(const Vec3& p) const {
    if (near_.empty()) return false;
    long c[3];
    if (!cellOf(p, c)) return false;
    const Scalar reach2 = Scalar(0.999 * 0.999) * dx_ * dx_;
    long n[3];
    for (int k = (dim_ == 3 ? -1 : 0); k <= (dim_ == 3 ? 1 : 0); ++k)
        for (int j = -1; j <= 1; ++j)
            for (int i = -1; i <= 1; ++i) {
                n[0] = c[0] + i;
                n[1] = c[1] + j;
                n[2] = c[2] + k;
                if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= cells_[0] || n[1] >= cells_[1] || n[2] >= cells_[2])
                    continue;
                const std::uint64_t cell = key(n);
                for (auto it = std::lower_bound(near_.begin(), near_.end(), std::make_pair(cell, std::size_t(0)));
                     it != near_.end() && it->first == cell; ++it)
                    if (((*placed_)[it->second] - p).squaredNorm() < reach2) return true;
            }
    return false;
}

std::vector<Scalar> depthsBelowFreeSurface(const std::vector<Vec3>& positions, const Vec3& up, Scalar dx, int dim,
                                           std::size_t solidFrom) {
    const std::size_t n = positions.size();
    std::vector<Scalar> depth(n, Scalar(0));
    if (n == 0 || !(up.norm() > 0)) return depth;
    // two directions across 'up' (one in 2D): a particle's column is its cell of Δx in them
    Vec3 across1 = up.unitOrthogonal();
    if (dim == 2) across1 = Vec3(up[1], -up[0], 0).normalized();
    const Vec3 across2 = up.cross(across1);
    struct Item {
        long c1, c2;
        Scalar height;
        std::size_t index;
    };
    std::vector<Item> items(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = positions[i];
        // (the cell's edges at k + 0.75 spacings: neither lattice of the case, (i + ½)Δx from the
        // origin or from a box's min on a multiple of Δx, lies on one, where rounding would split
        // the points of one column between two)
        const auto cell = [&](const Vec3& axis) { return long(std::floor(p.dot(axis) / dx + Scalar(0.25))); };
        items[i] = {cell(across1), dim == 3 ? cell(across2) : 0L, p.dot(up), i};
    }
    // each column from its top down
    std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
        return a.c1 != b.c1 ? a.c1 < b.c1 : a.c2 != b.c2 ? a.c2 < b.c2 : a.height > b.height;
    });
    const Scalar gap = Scalar(1.5) * dx;
    Scalar surface = 0, last = 0;
    bool inWater = false, lastSolid = false;
    for (std::size_t k = 0; k < n; ++k) {
        const Item& it = items[k];
        if (k == 0 || it.c1 != items[k - 1].c1 || it.c2 != items[k - 1].c2) inWater = false;
        if (it.index >= solidFrom) { // a solid: it bridges the water above it to the water below
            if (inWater) {
                last = it.height;
                lastSolid = true;
            }
            continue;
        }
        // (the water keeps half a spacing clear of a solid's surface, more than that along a
        // column where the surface is steep: the water next below a bridging solid continues it)
        if (!inWater || (!lastSolid && last - it.height > gap)) surface = it.height + dx / 2;
        inWater = true;
        last = it.height;
        lastSolid = false;
        depth[it.index] = surface - it.height;
    }
    return depth;
}

namespace {
// A `type mesh` wall: `sampling lattice` (default; `layers`, `side inside|outside`) or
// `sampling poissonDisk` (`spacing` in Δx; one layer on the surface, open or closed).
void sampleMeshWall(const Dictionary& w, Scalar dx, int dim, SampledWall& sampled) {
    const bool poisson = w.getWordOrDefault("sampling", {"lattice", "poissonDisk"}, "lattice") == "poissonDisk";
    const auto mesh = readMesh(w, !poisson, "a wall of `sampling lattice`");
    sampled.mesh = mesh;
    sampled.meshClosed = mesh->openEdges() == 0;
    if (w.found("side") && !sampled.meshClosed)
        throw InputError(w.locationOf("side"), "'side' needs a closed mesh: '" + mesh->name() +
                                                   "' is open (its particles lie on its surface)", "side");
    sampled.meshOutside = w.getWordOrDefault("side", {"inside", "outside"}, "inside") == "outside";
    const TriangleMesh::V lo = mesh->boundsMin(), hi = mesh->boundsMax();
    sampled.min = Vec3(Scalar(lo[0]), Scalar(lo[1]), dim == 3 ? Scalar(lo[2]) : Scalar(0));
    sampled.max = Vec3(Scalar(hi[0]), Scalar(hi[1]), dim == 3 ? Scalar(hi[2]) : Scalar(0));
    if (dim == 2 && !(lo[2] < 0 && hi[2] > 0))
        throw InputError(w.locationOf("file"), "mesh '" + mesh->name() + "' does not cross the plane z = 0, "
                                               "which a 2D case takes its section from", "file");
    if (poisson) {
        if (w.found("layers"))
            throw InputError(w.locationOf("layers"), "'layers' is for `sampling lattice`: a Poisson-disk wall is "
                                                     "one layer on the surface", "layers");
        const double spacing = w.getOrDefault<double>("spacing", 0.5);
        if (!(spacing >= 0.25 && spacing <= 4))
            throw InputError(w.locationOf("spacing"), "'spacing' (the least distance between wall particles, "
                                                      "in particleSpacing) must be within 0.25 to 4 (default 0.5)", "spacing");
        sampled.thickness = Scalar(spacing) * dx;
        SurfaceSamples samples = poissonDiskSurface(*mesh, spacing * double(dx), dim);
        sampled.positions = std::move(samples.positions);
        sampled.normals = std::move(samples.normals);
        sampled.surfaceSpacing = Scalar(spacing) * dx;
    } else {
        if (w.found("spacing"))
            throw InputError(w.locationOf("spacing"), "'spacing' is for `sampling poissonDisk` (a lattice wall "
                                                      "takes particleSpacing)", "spacing");
        const int layers = w.getOrDefault<int>("layers", 3);
        if (layers < 1) throw InputError(w.locationOf("layers"), "'layers' must be at least 1", "layers");
        sampled.thickness = layers * dx;
        sampled.positions = latticeLayers(*mesh, dx, dim, sampled.thickness, sampled.meshOutside);
    }
    if (sampled.positions.empty())
        throw InputError(w.where(), "wall '" + sampled.name + "' produced no particles (is its mesh smaller than "
                                    "particleSpacing, or in 2D, is its section by z = 0 empty?)");
}

// A mesh entry's particles, from its surface area and box (an upper bound of the order of the count).
double meshEstimate(const Dictionary& d, Scalar dx, int dim, bool fluid) {
    const auto mesh = readMesh(d, false, "");
    const TriangleMesh::V size = mesh->boundsMax() - mesh->boundsMin();
    const double h = double(dx);
    if (fluid) return dim == 3 ? size.prod() / (h * h * h) : size[0] * size[1] / (h * h);
    const bool poisson = d.getWordOrDefault("sampling", {"lattice", "poissonDisk"}, "lattice") == "poissonDisk";
    const double layers = poisson ? 1.0 : d.getOrDefault<double>("layers", 3);
    const double spacing = poisson ? d.getOrDefault<double>("spacing", 0.5) : 1.0;
    // 2D: the section's length is at most the box's perimeter... times the triangles crossing it
    const double surface = dim == 3 ? mesh->area() / (h * h) : 2 * (size[0] + size[1]) / h;
    return surface * layers / std::pow(spacing, dim - 1);
}
} // namespace

ParticleEstimate estimateParticleCount(const Dictionary& geometry, Scalar dx, int dim) {
    // lattice points in a box (in double: a count beyond any integer type must not overflow)
    const auto points = [&](const Vec3& lo, const Vec3& hi) {
        double n = 1;
        for (int a = 0; a < dim; ++a) n *= std::max(0.0, std::round(double(hi[a] - lo[a]) / double(dx)));
        return n;
    };
    ParticleEstimate e;
    const auto add = [&](double n, const std::string& name, const SourceLocation& where) {
        e.count += n;
        if (n > e.largest) {
            e.largest = n;
            e.largestName = name;
            e.largestAt = where;
        }
    };
    if (const Dictionary* walls = geometry.findDict("walls"))
        for (const auto& name : walls->keywords()) {
            const Dictionary& w = walls->subDict(name);
            const std::string type = w.getWord("type", wallTypes());
            if (type == "mesh") { // (its own sampling: sampleMeshWall)
                add(meshEstimate(w, dx, dim, false), "walls." + name, walls->locationOf(name));
                continue;
            }
            if (type != "container") {
                add(latticePointCount(*readShape(w, dim, dx), dx), "walls." + name, walls->locationOf(name));
                continue;
            }
            const Box box = readBox(w, dim);
            const double layers = w.getOrDefault<double>("layers", 3);
            Vec3 lo = box.min, hi = box.max;
            for (int a = 0; a < dim; ++a) {
                lo[a] -= Scalar(layers * dx);
                hi[a] += Scalar(layers * dx);
            }
            add(std::max(0.0, points(lo, hi) - points(box.min, box.max)), "walls." + name, walls->locationOf(name));
        }
    if (const Dictionary* fluid = geometry.findDict("fluid"))
        for (const auto& name : fluid->keywords()) {
            const double n = latticePointCount(*readShape(fluid->subDict(name), dim, dx), dx);
            add(n, "fluid." + name, fluid->locationOf(name));
            e.fluid += n;
        }
    if (const Dictionary* bodies = geometry.findDict("bodies"))
        for (const auto& name : bodies->keywords()) {
            add(latticePointCount(*readShape(bodies->subDict(name), dim, dx), dx), "bodies." + name,
                bodies->locationOf(name));
        }
    return e;
}

SampledGeometry sampleGeometry(const Dictionary& geometry, Scalar dx, int dim, const Vec3& gravity) {
    SampledGeometry out;
    std::vector<std::size_t> meshWalls; // (indices into out.walls: it grows)
    std::vector<std::shared_ptr<const Shape>> solids;
    std::vector<std::pair<std::string, Box>> containers;

    if (const Dictionary* walls = geometry.findDict("walls")) {
        for (const auto& name : walls->keywords()) {
            const Dictionary& w = walls->subDict(name);
            const std::string type = w.getWord("type", wallTypes());
            checkName(*walls, name, "wall");
            if (name == "fluid")
                throw InputError(walls->locationOf(name), "a wall may not be called 'fluid' (the fluid's own "
                                                          "output is fluid.vtp)", name);
            SampledWall& sampled = out.walls.emplace_back();
            sampled.name = name;
            sampled.where = walls->locationOf(name);
            sampled.motion = w.findDict("motion");
            w.markUsed("motion");
            if (type == "mesh") {
                sampleMeshWall(w, dx, dim, sampled);
                meshWalls.push_back(&sampled - out.walls.data());
                w.checkAllKeywordsUsed();
                continue;
            }
            const int layers = w.getOrDefault<int>("layers", 3);
            if (layers < 1) throw InputError(w.locationOf("layers"), "'layers' must be at least 1", "layers");
            const Scalar L = layers * dx;
            sampled.container = type == "container";
            sampled.thickness = L;
            std::vector<Vec3>& wallPositions = sampled.positions;
            if (type == "container") {
                const Box box = readBox(w, dim);
                containers.emplace_back(name, box);
                bool open[6] = {false, false, false, false, false, false};
                for (const auto& face : w.getOrDefault<std::vector<std::string>>("open", {})) {
                    const int f = faceIndex(face);
                    if (f < 0 || f / 2 >= dim)
                        throw InputError(w.locationOf("open"), "unknown face '" + face +
                                         "' in 'open'; valid: (xMin xMax yMin yMax" +
                                         std::string(dim == 3 ? " zMin zMax)" : ")"), "open");
                    open[f] = true;
                }
                // Inner extent must be a whole number of spacings for the lattice to continue.
                Box inner = box;
                snapToLattice(inner, w, "walls." + name, dx, dim, "wall");
                const Vec3 lo = inner.min, hi = inner.max;
                sampled.min = lo;
                sampled.max = hi;
                std::copy(open, open + 6, sampled.open);
                Vec3 outerLo = lo, outerHi = hi;
                for (int a = 0; a < dim; ++a) {
                    outerLo[a] -= L;
                    outerHi[a] += L;
                }
                forEachLatticePoint(outerLo, outerHi, dx, dim, [&](const Vec3& p) {
                    bool outside = false;
                    for (int a = 0; a < dim; ++a) {
                        if (p[a] < lo[a] && !open[2 * a]) outside = true;
                        if (p[a] > hi[a] && !open[2 * a + 1]) outside = true;
                    }
                    // open faces: drop the whole slab beyond them
                    for (int a = 0; a < dim; ++a) {
                        if (p[a] < lo[a] && open[2 * a]) outside = false;
                        if (p[a] > hi[a] && open[2 * a + 1]) outside = false;
                    }
                    if (outside) wallPositions.push_back(p);
                });
            } else { // a solid: the `layers` outermost lattice layers inside its surface
                sampled.shape = snappedShape(w, "walls." + name, dx, dim, "wall");
                solids.push_back(sampled.shape);
                sampled.shape->bounds(sampled.min, sampled.max);
                sampleShape(*sampled.shape, dx, L, wallPositions);
            }
            if (wallPositions.empty())
                throw InputError(w.where(), "wall '" + name + "' produced no particles (is it smaller than particleSpacing?)");
            w.checkAllKeywordsUsed();
        }
    }

    // rigid bodies: solid blocks, each a system of its own (its mass properties and constraints
    // are read by the caller, rigidBodyFrom)
    if (const Dictionary* bodies = geometry.findDict("bodies")) {
        for (const auto& name : bodies->keywords()) {
            const Dictionary& b = bodies->subDict(name);
            std::shared_ptr<const Shape> shape = snappedShape(b, "bodies." + name, dx, dim, "body");
            const int layers = b.getOrDefault<int>("layers", 3);
            if (layers < 1) throw InputError(b.locationOf("layers"), "'layers' must be at least 1", "layers");
            if (name == "fluid" || (geometry.findDict("walls") && geometry.subDict("walls").found(name)))
                throw InputError(bodies->locationOf(name), "a body may not share its name with the fluid or a wall", name);
            checkName(*bodies, name, "body");
            solids.push_back(shape);
            SampledWall& sampled = out.walls.emplace_back();
            sampled.name = name;
            sampled.where = bodies->locationOf(name);
            shape->bounds(sampled.min, sampled.max);
            sampled.shape = shape;
            sampled.body = &b;
            sampled.mass = massProperties(*shape, dx);
            sampleShape(*shape, dx, layers * dx, sampled.positions);
            if (sampled.positions.empty())
                throw InputError(b.where(), "body '" + name + "' produced no particles (is it smaller than particleSpacing?)");
        }
    }

    if (const Dictionary* periodic = geometry.findDict("periodic")) {
        for (const auto& axisName : periodic->keywords()) {
            const int a = axisName == "x" ? 0 : axisName == "y" ? 1 : axisName == "z" ? 2 : -1;
            if (a < 0 || a >= dim)
                throw InputError(periodic->locationOf(axisName), "unknown periodic axis '" + axisName +
                                 "'; valid: (x y" + std::string(dim == 3 ? " z)" : ")"), axisName);
            const auto range = periodic->get<std::vector<double>>(axisName);
            if (range.size() != 2 || !(range[1] > range[0]))
                throw InputError(periodic->locationOf(axisName), "periodic axis '" + axisName +
                                 "' needs (min max) with max > min", axisName);
            const double cells = (range[1] - range[0]) / dx;
            if (std::abs(cells - std::round(cells)) > 1e-6 * cells)
                throw InputError(periodic->locationOf(axisName), "the periodic length along " + axisName +
                                 " must be a whole number of particleSpacing", axisName);
            out.periodic.axis[a] = true;
            out.periodic.min[a] = Scalar(range[0]);
            out.periodic.length[a] = Scalar(range[1] - range[0]);
        }
    }

    const Dictionary& fluid = geometry.subDict("fluid");
    // a run without fluid would overwrite the case's results with empty states
    if (fluid.keywords().empty())
        throw InputError(geometry.locationOf("fluid"), "'fluid' has no block: nothing to simulate (e.g. "
                                                       "'water { type box; min (..); max (..); }')", "fluid");
    // A fluid particle is removed inside a solid wall or body, or nearer one of its particles than
    // Δx: the water fills the lattice up to the solid's particles, as the wall particles fill it up
    // to the water. (A clearance from the solid's surface instead left the lattice points within it
    // empty on a slope or a curve, half a particle a column on a 1:20 beach: the water settled into
    // them and its level fell 5 mm in 0.5 m.) Mesh walls the same; a closed one's inside is decided
    // by its winding number, and a vessel's shell (`side outside`: outside its surface, within its
    // thickness and Δx of it) is removed too.
    PointGrid solidPoints(double(dx), dim);
    for (const SampledWall& w : out.walls)
        if (!w.container)
            for (const Vec3& p : w.positions) solidPoints.add(p);
    const auto inSolid = [&](const Vec3& p) {
        if (solidPoints.anyWithin(p, Scalar(0.999) * dx)) return true;
        for (const auto& s : solids)
            if (s->contains(p, 0)) return true;
        for (const std::size_t k : meshWalls) {
            const SampledWall& w = out.walls[k];
            if (!w.meshClosed) continue;
            const TriangleMesh::V q = p.cast<double>();
            if (w.meshOutside) {
                const double reach = double(w.thickness + dx);
                if (!w.mesh->inside(q) && w.mesh->distance(q, reach) < reach) return true;
            } else if (w.mesh->inside(q)) {
                return true;
            }
        }
        return false;
    };
    OccupiedSpace occupied(dx, dim);
    std::vector<char> hydrostaticParticle;
    Vec3 up = Vec3::Zero();
    for (const auto& name : fluid.keywords()) {
        const Dictionary& f = fluid.subDict(name);
        checkName(fluid, name, "fluid block");
        const std::unique_ptr<Shape> shape = snappedShape(f, "fluid." + name, dx, dim, "fluid block");
        Box box;
        shape->bounds(box.min, box.max);
        if (!containers.empty()) {
            const Scalar tol = Scalar(1e-9) + Scalar(1e-6) * dx;
            bool inside = false;
            for (const auto& [wallName, c] : containers)
                inside = inside || (c.contains(box.min, dim, tol) && c.contains(box.max, dim, tol));
            if (!inside) {
                std::ostringstream s;
                s << "fluid block '" << name << "' lies outside every wall: it must fit inside a container (";
                const auto point = [&](const Vec3& p) {
                    for (int k = 0; k < dim; ++k) s << (k ? " " : "") << p[k];
                };
                for (const auto& [wallName, c] : containers) {
                    s << wallName << " spans (";
                    point(c.min);
                    s << ") to (";
                    point(c.max);
                    s << ") ";
                }
                s << ")";
                throw InputError(f.where(), s.str());
            }
        }
        const VelocityField velocity = readVelocity(f, dim);
        // initialPressure zero | hydrostatic | "<expression of x, y, z>"
        std::unique_ptr<Expression> pressure;
        bool hydrostatic = false;
        if (const Entry* e = f.findEntry("initialPressure");
            e && !e->isDict() && e->tokens.size() == 1 && e->tokens[0].kind == Token::Kind::String) {
            f.markUsed("initialPressure");
            pressure = std::make_unique<Expression>(e->tokens[0].text, e->tokens[0].where, "initialPressure");
        } else {
            hydrostatic = f.getWordOrDefault("initialPressure", {"zero", "hydrostatic"}, "zero") == "hydrostatic";
        }
        const Scalar g = gravity.norm();
        if (hydrostatic && !(g > 0))
            throw InputError(f.locationOf("initialPressure"), "initialPressure hydrostatic needs gravity "
                                                               "(constant/fluidProperties)", "initialPressure");
        if (g > 0) up = -gravity / g;
        const std::size_t before = out.fluidPositions.size();
        std::size_t shared = 0;
        occupied.beginRegion(out.fluidPositions, box.min, box.max);
        std::vector<Vec3> candidates;
        sampleShape(*shape, dx, 0, candidates);
        for (const Vec3& p : candidates) {
            if (inSolid(p)) continue;
            if (occupied.filled(p)) {
                ++shared;
                continue;
            }
            out.fluidPositions.push_back(p);
            out.fluidVelocities.push_back(velocity.at(p, dim));
            out.fluidPressures.push_back(pressure ? Scalar((*pressure)(p)) : Scalar(0));
            hydrostaticParticle.push_back(hydrostatic);
        }
        occupied.endRegion(out.fluidPositions);
        const std::size_t count = out.fluidPositions.size() - before;
        out.fluidBlocks.push_back({name, fluid.locationOf(name), before, count, box.min, box.max});
        if (shared > 0) {
            std::ostringstream s;
            s << "fluid block '" << name << "' overlaps the blocks before it: " << shared << " of its positions are "
              << "filled already and are not filled twice (" << count << " particles added)";
            log::warning(locatedMessage(fluid.locationOf(name), "", s.str()));
        }
        if (count == 0 && shared == 0)
            throw InputError(f.where(), "fluid block '" + name + "' produced no particles (is it smaller than "
                                        "particleSpacing, or inside a wall?)");
        f.checkAllKeywordsUsed();
    }
    // A mesh wall far from the fluid is a mesh in other units or misplaced (a tank in millimetres
    // read as metres): more than ten times the fluid's size away from it.
    if (!meshWalls.empty() && !out.fluidPositions.empty()) {
        Vec3 flo = out.fluidPositions[0], fhi = flo;
        for (const Vec3& p : out.fluidPositions) {
            flo = flo.cwiseMin(p);
            fhi = fhi.cwiseMax(p);
        }
        const double size = std::max(double((fhi - flo).norm()), 10 * double(dx));
        for (const std::size_t k : meshWalls) {
            const SampledWall& w = out.walls[k];
            double gap2 = 0;
            for (int a = 0; a < dim; ++a) {
                const double g = std::max({0.0, double(w.min[a] - fhi[a]), double(flo[a] - w.max[a])});
                gap2 += g * g;
            }
            if (std::sqrt(gap2) > 10 * size) {
                std::ostringstream m;
                const auto point = [&](const Vec3& p) {
                    std::ostringstream t;
                    for (int a = 0; a < dim; ++a) t << (a ? " " : "") << p[a];
                    return t.str();
                };
                m << "mesh '" << w.mesh->name() << "' of wall '" << w.name << "' lies far outside the domain: its "
                  << "box (" << point(w.min) << ") to (" << point(w.max) << ") is " << std::sqrt(gap2)
                  << " m from the fluid's (" << point(flo) << ") to (" << point(fhi)
                  << "); check its units, 'scale' and 'translate'";
                throw InputError(geometry.subDict("walls").subDict(w.name).locationOf("file"), m.str(), "file");
            }
        }
    }
    // the hydrostatic start: the depth below the fluid's free surface above each particle, over
    // every block (stacked blocks start as one column)
    out.fluidDepths.assign(out.fluidPositions.size(), Scalar(0));
    if (std::find(hydrostaticParticle.begin(), hydrostaticParticle.end(), char(1)) != hydrostaticParticle.end()) {
        // a body in the water does not end its column: the water below it bears it (filled with
        // its lattice for the columns, exact for a body of the water's density)
        std::vector<Vec3> columns = out.fluidPositions;
        for (const SampledWall& w : out.walls)
            if (w.body) sampleShape(*w.shape, dx, 0, columns);
        // a solid wall under water does not end its column either: the water below it is as deep
        // as the water above it (its points bridge the column where water lies above them)
        const std::size_t solidFrom = columns.size();
        for (const SampledWall& w : out.walls)
            if (!w.body && w.shape) sampleShape(*w.shape, dx, 0, columns);
        std::vector<Scalar> depths = depthsBelowFreeSurface(columns, up, dx, dim, solidFrom);
        depths.resize(out.fluidPositions.size());
        for (std::size_t i = 0; i < depths.size(); ++i)
            if (hydrostaticParticle[i]) out.fluidDepths[i] = depths[i];
    }
    geometry.checkAllKeywordsUsed();

    Vec3 lo = Vec3::Constant(std::numeric_limits<Scalar>::max()), hi = -lo;
    const auto include = [&](const std::vector<Vec3>& points) {
        for (const auto& p : points) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    };
    include(out.fluidPositions);
    for (const auto& w : out.walls) include(w.positions);
    if (dim == 2) lo[2] = hi[2] = 0;
    out.boundsMin = lo;
    out.boundsMax = hi;
    return out;
}

} // namespace spindrift
