#include "Shape.hpp"

#include "Error.hpp"
#include "MeshShape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace spindrift {
namespace {

using V3d = Eigen::Vector3d;

std::string str(const Vec3& v, int dim) {
    std::ostringstream s;
    s << "(";
    for (int a = 0; a < dim; ++a) s << (a ? " " : "") << v[a];
    s << ")";
    return s.str();
}

Scalar positive(const Dictionary& d, const char* key) {
    const double v = d.get<double>(key);
    if (!(v > 0) || !std::isfinite(v))
        throw InputError(d.locationOf(key), std::string("'") + key + "' must be a positive number", key);
    return Scalar(v);
}

Vec3 finitePoint(const Dictionary& d, const char* key, int dim) {
    Vec3 v = d.get<Vec3>(key);
    if (!v.allFinite()) throw InputError(d.locationOf(key), std::string("'") + key + "' must be finite", key);
    if (dim == 2) v[2] = 0;
    return v;
}

// ---- box -------------------------------------------------------------------------------------
class BoxShape final : public Shape {
public:
    BoxShape(const Vec3& lo, const Vec3& hi, int dim) : Shape(dim), lo_(lo), hi_(hi) {}
    Scalar signedDistance(const Vec3& p) const override {
        // per axis how far outside each pair of faces (negative inside); exact Euclidean outside
        Scalar inside = -std::numeric_limits<Scalar>::max(), outside2 = 0;
        bool out = false;
        for (int a = 0; a < dim_; ++a) {
            const Scalar q = std::max(lo_[a] - p[a], p[a] - hi_[a]);
            inside = std::max(inside, q);
            if (q > 0) {
                out = true;
                outside2 += q * q;
            }
        }
        return out ? std::sqrt(outside2) : inside;
    }
    bool contains(const Vec3& p, Scalar margin) const override {
        for (int a = 0; a < dim_; ++a)
            if (p[a] < lo_[a] - margin || p[a] > hi_[a] + margin) return false;
        return true;
    }
    void bounds(Vec3& lo, Vec3& hi) const override {
        lo = lo_;
        hi = hi_;
    }
    void lattice(Scalar dx, Vec3& origin, long cells[3]) const override {
        // as it always was: round(size/Δx) cells from min (a wall box is a whole number of them)
        origin = lo_;
        for (int a = 0; a < 3; ++a) {
            const double n = a < dim_ ? std::max(0.0, std::round(double(hi_[a] - lo_[a]) / double(dx))) : 1.0;
            cells[a] = n < 1e15 ? long(n) : long(1e15);
        }
    }
    bool isBox() const override { return true; }
    std::string describe() const override { return "box min " + str(lo_, dim_) + " max " + str(hi_, dim_); }

private:
    Vec3 lo_, hi_;
};

// ---- sphere (2D: circle) -----------------------------------------------------------------------
class SphereShape final : public Shape {
public:
    SphereShape(const Vec3& c, Scalar r, int dim, std::string type) : Shape(dim), c_(c), r_(r), type_(std::move(type)) {}
    Scalar signedDistance(const Vec3& p) const override {
        Vec3 d = p - c_;
        if (dim_ == 2) d[2] = 0;
        return Scalar(d.cast<double>().norm() - double(r_));
    }
    void bounds(Vec3& lo, Vec3& hi) const override {
        lo = c_ - Vec3::Constant(r_);
        hi = c_ + Vec3::Constant(r_);
        if (dim_ == 2) lo[2] = hi[2] = 0;
    }
    std::string describe() const override {
        std::ostringstream s;
        s << type_ << " centre " << str(c_, dim_) << " radius " << r_;
        return s.str();
    }

private:
    Vec3 c_;
    Scalar r_;
    std::string type_;
};

// ---- cylinder in 3D: axis from p1 to p2, flat caps -----------------------------------------------
class CylinderShape final : public Shape {
public:
    CylinderShape(const Vec3& p1, const Vec3& p2, Scalar r) : Shape(3), p1_(p1), p2_(p2), r_(r) {
        const V3d axis = (p2 - p1).cast<double>();
        length_ = axis.norm();
        u_ = axis / length_;
    }
    Scalar signedDistance(const Vec3& p) const override {
        const V3d q = (p - p1_).cast<double>();
        const double t = q.dot(u_);
        const double radial = (q - t * u_).norm() - double(r_);
        const double along = std::abs(t - length_ / 2) - length_ / 2;
        const double outside = std::hypot(std::max(radial, 0.0), std::max(along, 0.0));
        return Scalar(std::min(std::max(radial, along), 0.0) + outside);
    }
    void bounds(Vec3& lo, Vec3& hi) const override {
        for (int a = 0; a < 3; ++a) {
            const double e = double(r_) * std::sqrt(std::max(0.0, 1 - u_[a] * u_[a]));
            lo[a] = Scalar(std::min(p1_[a], p2_[a]) - e);
            hi[a] = Scalar(std::max(p1_[a], p2_[a]) + e);
        }
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "cylinder point1 " << str(p1_, 3) << " point2 " << str(p2_, 3) << " radius " << r_;
        return s.str();
    }

private:
    Vec3 p1_, p2_;
    Scalar r_;
    V3d u_;
    double length_;
};

// ---- polygon (2D) ------------------------------------------------------------------------------
double cross2(const V3d& a, const V3d& b) { return a[0] * b[1] - a[1] * b[0]; }

// whether segments ab and cd meet (touching counts)
bool segmentsMeet(const V3d& a, const V3d& b, const V3d& c, const V3d& d) {
    const auto orient = [](const V3d& p, const V3d& q, const V3d& r) {
        const double v = cross2(q - p, r - p);
        return v > 0 ? 1 : v < 0 ? -1 : 0;
    };
    const auto onSegment = [](const V3d& p, const V3d& q, const V3d& r) { // r on pq, given collinear
        return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) && std::min(p[1], q[1]) <= r[1] &&
               r[1] <= std::max(p[1], q[1]);
    };
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) || (o3 == 0 && onSegment(c, d, a)) ||
           (o4 == 0 && onSegment(c, d, b));
}

class PolygonShape final : public Shape {
public:
    explicit PolygonShape(std::vector<V3d> points) : Shape(2), v_(std::move(points)) {}
    Scalar signedDistance(const Vec3& pIn) const override {
        const V3d p(static_cast<double>(pIn[0]), static_cast<double>(pIn[1]), 0.0);
        double d2 = std::numeric_limits<double>::max();
        int winding = 0; // Hormann & Agathos 2001: crossings of the ray +x, signed by direction
        const std::size_t n = v_.size();
        for (std::size_t i = 0; i < n; ++i) {
            const V3d& a = v_[i];
            const V3d& b = v_[(i + 1) % n];
            const V3d e = b - a, w = p - a;
            const double t = std::clamp(w.dot(e) / e.dot(e), 0.0, 1.0);
            d2 = std::min(d2, (w - t * e).squaredNorm());
            if (a[1] <= p[1]) {
                if (b[1] > p[1] && cross2(e, w) > 0) ++winding;
            } else if (b[1] <= p[1] && cross2(e, w) < 0) {
                --winding;
            }
        }
        const double d = std::sqrt(d2);
        return Scalar(winding != 0 ? -d : d);
    }
    void bounds(Vec3& lo, Vec3& hi) const override {
        V3d l = v_[0], h = v_[0];
        for (const V3d& p : v_) {
            l = l.cwiseMin(p);
            h = h.cwiseMax(p);
        }
        lo = l.cast<Scalar>();
        hi = h.cast<Scalar>();
        lo[2] = hi[2] = 0;
    }
    std::string describe() const override {
        std::ostringstream s;
        s << "polygon of " << v_.size() << " points";
        return s.str();
    }

private:
    std::vector<V3d> v_;
};

// ---- A − B − C ... -------------------------------------------------------------------------------
class DifferenceShape final : public Shape {
public:
    DifferenceShape(std::unique_ptr<Shape> a, std::vector<std::unique_ptr<Shape>> cut)
        : Shape(a->dimension()), a_(std::move(a)), cut_(std::move(cut)) {}
    Scalar signedDistance(const Vec3& p) const override {
        Scalar d = a_->signedDistance(p);
        for (const auto& c : cut_) d = std::max(d, -c->signedDistance(p));
        return d;
    }
    bool contains(const Vec3& p, Scalar margin) const override {
        if (!a_->contains(p, margin)) return false;
        for (const auto& c : cut_)
            if (c->contains(p, -margin)) return false;
        return true;
    }
    void bounds(Vec3& lo, Vec3& hi) const override { a_->bounds(lo, hi); }
    void lattice(Scalar dx, Vec3& origin, long cells[3]) const override { a_->lattice(dx, origin, cells); }
    std::string describe() const override {
        std::string s = a_->describe() + " minus (";
        for (std::size_t i = 0; i < cut_.size(); ++i) s += (i ? ", " : "") + cut_[i]->describe();
        return s + ")";
    }

private:
    std::unique_ptr<Shape> a_;
    std::vector<std::unique_ptr<Shape>> cut_;
};

std::unique_ptr<Shape> readPolygon(const Dictionary& d) {
    const auto given = d.get<std::vector<Vec3>>("points");
    std::vector<V3d> v;
    for (const Vec3& p : given) {
        if (!p.allFinite()) throw InputError(d.locationOf("points"), "'points' must be finite", "points");
        const V3d q(static_cast<double>(p[0]), static_cast<double>(p[1]), 0.0);
        if (!v.empty() && q == v.back()) continue; // a repeated point (or the first repeated last)
        v.push_back(q);
    }
    if (v.size() > 1 && v.front() == v.back()) v.pop_back();
    if (v.size() < 3)
        throw InputError(d.locationOf("points"), "a polygon needs at least 3 distinct points ((x y 0) each)", "points");
    double area2 = 0;
    for (std::size_t i = 0; i < v.size(); ++i) area2 += cross2(v[i], v[(i + 1) % v.size()]);
    const std::size_t n = v.size();
    V3d lo = v[0], hi = v[0];
    for (const V3d& p : v) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    if (!(std::abs(area2) > 1e-12 * (hi - lo).squaredNorm()))
        throw InputError(d.locationOf("points"), "the polygon encloses no area (are its points on one line?)", "points");
    // simple: no two edges that are not neighbours meet
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue; // neighbours across the closing edge
            if (segmentsMeet(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
                std::ostringstream s;
                s << "the polygon crosses itself: edge " << i << " (point " << i << " to " << (i + 1) % n
                  << ") meets edge " << j << " (point " << j << " to " << (j + 1) % n
                  << "); list its points in order around it";
                throw InputError(d.locationOf("points"), s.str(), "points");
            }
        }
    return std::make_unique<PolygonShape>(std::move(v));
}

} // namespace

void Shape::lattice(Scalar dx, Vec3& origin, long cells[3]) const {
    // the case lattice, (i + ½)Δx from the origin, over the shape's bounds
    Vec3 lo, hi;
    bounds(lo, hi);
    origin = Vec3::Zero();
    for (int a = 0; a < 3; ++a) {
        if (a >= dim_) {
            cells[a] = 1;
            continue;
        }
        const double first = std::floor(double(lo[a]) / double(dx));
        const double n = std::ceil(double(hi[a]) / double(dx)) - first;
        origin[a] = Scalar(first * double(dx));
        cells[a] = n < 0 ? 0 : n < 1e15 ? long(n) : long(1e15);
    }
}

std::unique_ptr<Shape> makeBox(const Vec3& lo, const Vec3& hi, int dim) { return std::make_unique<BoxShape>(lo, hi, dim); }

const std::vector<std::string>& shapeTypes() {
    static const std::vector<std::string> types{"box", "cylinder", "sphere", "polygon", "mesh"};
    return types;
}

std::unique_ptr<Shape> readShape(const Dictionary& d, int dim, Scalar dx, const std::vector<std::string>& allowed) {
    const std::string type = d.getWord("type", allowed.empty() ? shapeTypes() : allowed);
    std::unique_ptr<Shape> shape;
    if (type == "box") {
        Vec3 lo = d.get<Vec3>("min"), hi = d.get<Vec3>("max");
        for (int a = 0; a < dim; ++a)
            if (!(hi[a] > lo[a])) {
                std::ostringstream s;
                s << "'max' must exceed 'min' in every direction (axis " << "xyz"[a] << ": min " << lo[a] << ", max "
                  << hi[a] << ") in " << d.name();
                throw InputError(d.locationOf("max"), s.str(), "max");
            }
        if (dim == 2) lo[2] = hi[2] = 0;
        shape = std::make_unique<BoxShape>(lo, hi, dim);
    } else if (type == "sphere" || (type == "cylinder" && dim == 2)) {
        if (type == "cylinder" && (d.found("point1") || d.found("point2")))
            throw InputError(d.locationOf(d.found("point1") ? "point1" : "point2"),
                             "a 2D cylinder is a circle: give its 'centre' and 'radius' (point1 and point2 are "
                             "its axis in 3D)",
                             d.found("point1") ? "point1" : "point2");
        shape = std::make_unique<SphereShape>(finitePoint(d, "centre", dim), positive(d, "radius"), dim, type);
    } else if (type == "cylinder") {
        if (d.found("centre"))
            throw InputError(d.locationOf("centre"), "a 3D cylinder is given by its axis' end points 'point1' and "
                             "'point2' and its 'radius' ('centre' is a 2D circle's)", "centre");
        const Vec3 p1 = finitePoint(d, "point1", 3), p2 = finitePoint(d, "point2", 3);
        const Scalar r = positive(d, "radius");
        if (!((p2 - p1).norm() > 0))
            throw InputError(d.locationOf("point2"), "the cylinder's 'point2' must differ from 'point1'", "point2");
        shape = std::make_unique<CylinderShape>(p1, p2, r);
    } else if (type == "mesh") { // MeshShape.cpp
        shape = readMeshShape(d, dim, dx);
    } else if (type == "polygon") {
        if (dim != 2)
            throw InputError(d.locationOf("type"), "a polygon is 2D only (in 3D use a box, cylinder, sphere or mesh)",
                             "type");
        shape = readPolygon(d);
    }
    if (const Dictionary* sub = d.findDict("subtract")) {
        std::vector<std::unique_ptr<Shape>> cut;
        for (const auto& name : sub->keywords()) {
            if (!sub->isDict(name))
                throw InputError(sub->locationOf(name), "'subtract' lists shapes, each '<name> { type ...; }'", name);
            const Dictionary& e = sub->subDict(name);
            cut.push_back(readShape(e, dim, dx));
            e.checkAllKeywordsUsed();
        }
        if (cut.empty())
            throw InputError(d.locationOf("subtract"), "'subtract' is empty: list the shapes to cut out, e.g. "
                             "'subtract { hole { type cylinder; centre (0 0 0); radius 0.1; } }'", "subtract");
        shape = std::make_unique<DifferenceShape>(std::move(shape), std::move(cut));
    }
    return shape;
}

void sampleShape(const Shape& s, Scalar dx, Scalar thickness, std::vector<Vec3>& out) {
    const bool all = thickness <= 0;
    const bool box = s.isBox();
    forEachLatticePoint(s, dx, [&](const Vec3& p) {
        if (all && box) { // a box's lattice lies in it (a point on its face as well, as ever)
            out.push_back(p);
            return;
        }
        const Scalar d = s.signedDistance(p);
        if (all ? d < 0 : (box || d < 0) && -d < thickness) out.push_back(p);
    });
}

double latticePointCount(const Shape& s, Scalar dx) {
    Vec3 o;
    long n[3];
    s.lattice(dx, o, n);
    return double(n[0]) * double(n[1]) * double(n[2]);
}

} // namespace spindrift
