#include "MeshShape.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace spindrift {

// A `type mesh` entry's surface: constant/triSurface/<file> (next to constant/geometry) read,
// placed (scale, then rotate (α β γ) degrees about x, y, z, then translate) and checked. A closed
// surface ('closed' needed, or found) must be consistently oriented with its normals outwards.
std::shared_ptr<TriangleMesh> readMesh(const Dictionary& d, bool needClosed, const char* why) {
    const std::string file = d.get<std::string>("file");
    const std::filesystem::path dir = std::filesystem::path(d.where().file).parent_path() / "triSurface";
    auto mesh = std::make_shared<TriangleMesh>(TriangleMesh::read(dir / file, d.locationOf("file")));
    const double scale = d.getOrDefault<double>("scale", 1.0);
    if (!(scale != 0) || !std::isfinite(scale))
        throw InputError(d.locationOf("scale"), "'scale' must be a nonzero number", "scale");
    const Vec3 rotate = d.getOrDefault<Vec3>("rotate", Vec3::Zero());
    const Vec3 translate = d.getOrDefault<Vec3>("translate", Vec3::Zero());
    mesh->transform(scale, rotate.cast<double>(), translate.cast<double>());
    const std::string path = (dir / file).string();
    const std::size_t open = mesh->openEdges(), flipped = mesh->inconsistentEdges();
    if (needClosed && open > 0)
        throw InputError(d.locationOf("file"), "mesh '" + path + "' is not closed: " + std::to_string(open) +
                                                   " of its edges are not shared by exactly two triangles (" + why +
                                                   " needs a closed surface)", "file");
    if (open == 0 && flipped > 0)
        throw InputError(d.locationOf("file"), "mesh '" + path + "' is not consistently oriented: " +
                                                   std::to_string(flipped) + " edges join triangles whose normals "
                                                   "point to opposite sides", "file");
    if (open == 0 && !(mesh->signedVolume() > 0)) {
        std::ostringstream s;
        s << "mesh '" << path << "' has inverted normals: its enclosed volume is " << mesh->signedVolume()
          << " (negative: the triangles are ordered clockwise seen from outside; reverse them)";
        throw InputError(d.locationOf("file"), s.str(), "file");
    }
    mesh->prepare();
    return mesh;
}


namespace {
class MeshShape final : public Shape {
public:
    MeshShape(std::shared_ptr<TriangleMesh> mesh, int dim, Scalar cap) : Shape(dim), mesh_(std::move(mesh)), cap_(cap) {}
    Scalar signedDistance(const Vec3& p) const override {
        const TriangleMesh::V q = point(p);
        const double d = std::min(mesh_->distance(q, double(cap_)), double(cap_));
        return Scalar(mesh_->inside(q) ? -d : d);
    }
    bool contains(const Vec3& p, Scalar margin) const override {
        if (margin == 0) return mesh_->inside(point(p));
        return signedDistance(p) < margin;
    }
    void bounds(Vec3& lo, Vec3& hi) const override {
        for (int a = 0; a < 3; ++a) {
            lo[a] = a < dim_ ? Scalar(mesh_->boundsMin()[a]) : Scalar(0);
            hi[a] = a < dim_ ? Scalar(mesh_->boundsMax()[a]) : Scalar(0);
        }
    }
    std::string describe() const override {
        return "mesh " + mesh_->name() + " (" + std::to_string(mesh_->triangles().size()) + " triangles)";
    }

private:
    TriangleMesh::V point(const Vec3& p) const { return TriangleMesh::V(double(p[0]), double(p[1]), dim_ == 3 ? double(p[2]) : 0.0); }
    std::shared_ptr<TriangleMesh> mesh_;
    Scalar cap_;
};
} // namespace

std::unique_ptr<Shape> readMeshShape(const Dictionary& d, int dim, Scalar dx) {
    auto mesh = readMesh(d, true, "a fluid region or a body");
    if (dim == 2 && !(mesh->boundsMin()[2] < 0 && mesh->boundsMax()[2] > 0))
        throw InputError(d.locationOf("file"), "mesh '" + mesh->name() + "' does not cross the plane z = 0, "
                                               "which a 2D case takes its section from", "file");
    // distances are needed exactly up to a body's layers (and the fluid's clearance of solids)
    const double layers = d.found("layers") ? d.get<double>("layers") : 3.0;
    const Scalar cap = Scalar(std::max(layers, 1.0) + 2) * dx;
    return std::make_unique<MeshShape>(std::move(mesh), dim, cap);
}

} // namespace spindrift
