#include "Geometry.hpp"

#include "Log.hpp"

#include <cmath>
#include <limits>
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

// The lattice points of a solid box that lie within 'thickness' of its surface (its outermost
// layers), appended to 'out'.
void solidBoxLayers(const Box& box, Scalar thickness, Scalar dx, int dim, std::vector<Vec3>& out) {
    forEachLatticePoint(box.min, box.max, dx, dim, [&](const Vec3& p) {
        Scalar depth = std::numeric_limits<Scalar>::max();
        for (int a = 0; a < dim; ++a) depth = std::min({depth, p[a] - box.min[a], box.max[a] - p[a]});
        if (depth < thickness) out.push_back(p);
    });
}

int faceIndex(const std::string& face) {
    static const char* names[6] = {"xMin", "xMax", "yMin", "yMax", "zMin", "zMax"};
    for (int i = 0; i < 6; ++i)
        if (face == names[i]) return i;
    return -1;
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
        if (n > e.largest) e = {e.count, n, name, where};
    };
    if (const Dictionary* walls = geometry.findDict("walls"))
        for (const auto& name : walls->keywords()) {
            const Dictionary& w = walls->subDict(name);
            const Box box = readBox(w, dim);
            const double layers = w.getOrDefault<double>("layers", 3);
            Vec3 lo = box.min, hi = box.max;
            for (int a = 0; a < dim; ++a) {
                lo[a] -= Scalar(layers * dx);
                hi[a] += Scalar(layers * dx);
            }
            add(w.getWordOrDefault("type", {"container", "box"}, "box") == "container"
                    ? std::max(0.0, points(lo, hi) - points(box.min, box.max))
                    : points(box.min, box.max),
                "walls." + name, walls->locationOf(name));
        }
    if (const Dictionary* fluid = geometry.findDict("fluid"))
        for (const auto& name : fluid->keywords()) {
            const Box box = readBox(fluid->subDict(name), dim);
            add(points(box.min, box.max), "fluid." + name, fluid->locationOf(name));
        }
    if (const Dictionary* bodies = geometry.findDict("bodies"))
        for (const auto& name : bodies->keywords()) {
            const Box box = readBox(bodies->subDict(name), dim);
            add(points(box.min, box.max), "bodies." + name, bodies->locationOf(name));
        }
    return e;
}

SampledGeometry sampleGeometry(const Dictionary& geometry, Scalar dx, int dim, const Vec3& gravity) {
    SampledGeometry out;
    std::vector<Box> solids;
    std::vector<std::pair<std::string, Box>> containers;

    if (const Dictionary* walls = geometry.findDict("walls")) {
        for (const auto& name : walls->keywords()) {
            const Dictionary& w = walls->subDict(name);
            const std::string type = w.getWord("type", {"container", "box"});
            const Box box = readBox(w, dim);
            const int layers = w.getOrDefault<int>("layers", 3);
            if (layers < 1) throw InputError(w.locationOf("layers"), "'layers' must be at least 1", "layers");
            const Scalar L = layers * dx;
            if (name == "fluid")
                throw InputError(walls->locationOf(name), "a wall may not be called 'fluid' (the fluid's own "
                                                          "output is fluid.vtp)", name);
            out.walls.push_back({name, {}, w.findDict("motion")});
            w.markUsed("motion");
            std::vector<Vec3>& wallPositions = out.walls.back().positions;
            if (type == "container") {
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
                Vec3 lo = box.min, hi = box.max;
                for (int a = 0; a < dim; ++a) {
                    const Scalar cells = std::round((hi[a] - lo[a]) / dx);
                    // (the tolerance allows for the rounding of a float build as well)
                    const Scalar tolerance = std::max(Scalar(1e-6) * dx, 64 * std::numeric_limits<Scalar>::epsilon() *
                                                                             (std::abs(lo[a]) + std::abs(hi[a])));
                    if (std::abs(cells * dx - (hi[a] - lo[a])) > tolerance) {
                        std::ostringstream s;
                        s << "walls." << name << ": size along " << "xyz"[a] << " is not a multiple of "
                          << "particleSpacing; the wall is placed at " << lo[a] + cells * dx;
                        log::warning(s.str());
                        hi[a] = lo[a] + cells * dx;
                    }
                }
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
            } else { // solid box: outermost layers inside the surface
                solids.push_back(box);
                solidBoxLayers(box, L, dx, dim, wallPositions);
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
            b.getWord("type", {"box"});
            const Box box = readBox(b, dim);
            const int layers = b.getOrDefault<int>("layers", 3);
            if (layers < 1) throw InputError(b.locationOf("layers"), "'layers' must be at least 1", "layers");
            if (name == "fluid" || (geometry.findDict("walls") && geometry.subDict("walls").found(name)))
                throw InputError(bodies->locationOf(name), "a body may not share its name with the fluid or a wall", name);
            solids.push_back(box);
            SampledWall& sampled = out.walls.emplace_back();
            sampled.name = name;
            sampled.body = &b;
            sampled.boxMin = box.min;
            sampled.boxMax = box.max;
            solidBoxLayers(box, layers * dx, dx, dim, sampled.positions);
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
    for (const auto& name : fluid.keywords()) {
        const Dictionary& f = fluid.subDict(name);
        f.getWord("type", {"box"});
        const Box box = readBox(f, dim);
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
        Vec3 velocity = f.getOrDefault<Vec3>("velocity", Vec3::Zero());
        if (dim == 2) velocity[2] = 0;
        // the top of the block along gravity: the highest of its corners
        const bool hydrostatic = f.getWordOrDefault("initialPressure", {"zero", "hydrostatic"}, "zero") == "hydrostatic";
        const Scalar g = gravity.norm();
        if (hydrostatic && !(g > 0))
            throw InputError(f.locationOf("initialPressure"), "initialPressure hydrostatic needs gravity "
                                                               "(constant/fluidProperties)", "initialPressure");
        const Vec3 up = g > 0 ? Vec3(-gravity / g) : Vec3::Zero();
        Scalar top = -std::numeric_limits<Scalar>::max();
        for (int corner = 0; corner < (1 << dim); ++corner) {
            Vec3 c = box.min;
            for (int a = 0; a < dim; ++a)
                if (corner & (1 << a)) c[a] = box.max[a];
            top = std::max(top, up.dot(c));
        }
        const std::size_t before = out.fluidPositions.size();
        forEachLatticePoint(box.min, box.max, dx, dim, [&](const Vec3& p) {
            for (const auto& s : solids)
                if (s.contains(p, dim)) return;
            out.fluidPositions.push_back(p);
            out.fluidVelocities.push_back(velocity);
            out.fluidDepths.push_back(hydrostatic ? top - up.dot(p) : Scalar(0));
        });
        if (out.fluidPositions.size() == before)
            throw InputError(f.where(), "fluid block '" + name + "' produced no particles (is it smaller than particleSpacing, or inside a wall?)");
        f.checkAllKeywordsUsed();
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
