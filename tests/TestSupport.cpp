#include "TestSupport.hpp"

#include "Simulation.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

namespace spindrift::test {

TempDir::TempDir(const std::string& prefix) {
    std::random_device rd;
    for (int attempt = 0; attempt < 100; ++attempt) {
        auto candidate = std::filesystem::temp_directory_path() /
                         (prefix + "-" + std::to_string(rd()));
        if (std::filesystem::create_directory(candidate)) {
            path_ = candidate;
            return;
        }
    }
    throw std::runtime_error("cannot create a temporary directory");
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::filesystem::path TempDir::writeFile(const std::string& relative, const std::string& text) const {
    auto file = path_ / relative;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream out(file);
    out << text;
    return file;
}

std::string readFile(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

double radialIntegral(const std::function<double(double)>& W, double h, int dim) {
    static const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    static const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
    const int n = 4096;
    const double dr = h / n;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int g = 0; g < 5; ++g) {
            const double r = (i + 0.5) * dr + 0.5 * dr * x[g];
            const double shell = dim == 2 ? 2 * std::numbers::pi * r : 4 * std::numbers::pi * r * r;
            sum += w[g] * 0.5 * dr * W(r) * shell;
        }
    return sum;
}

} // namespace spindrift::test

namespace spindrift::test {

PhysicalParameters physicsFor(int dim, Scalar dx, Scalar supportFactor, Scalar rho0) {
    PhysicalParameters p;
    p.dimension = dim;
    p.rho0 = rho0;
    p.particleSpacing = dx;
    p.supportRadius = supportFactor * dx;
    p.gravity = Vec3::Zero();
    return p;
}

void fillLattice(Scene& s, const Kernel& kernel, const Vec3& lo, const Vec3& hi) {
    const int dim = s.physics.dimension;
    const Scalar dx = s.physics.particleSpacing;
    std::vector<Vec3> points;
    const long nx = std::lround((hi[0] - lo[0]) / dx), ny = std::lround((hi[1] - lo[1]) / dx);
    const long nz = dim == 3 ? std::lround((hi[2] - lo[2]) / dx) : 1;
    for (long k = 0; k < nz; ++k)
        for (long j = 0; j < ny; ++j)
            for (long i = 0; i < nx; ++i)
                points.emplace_back(lo[0] + (i + 0.5) * dx, lo[1] + (j + 0.5) * dx,
                                    dim == 3 ? lo[2] + (k + 0.5) * dx : 0.0);
    s.kernel.build(kernel);
    s.fluid.resize(points.size());
    s.fluid.setParticleMass(latticeParticleMass(s.kernel, s.physics));
    s.constants.supportRadius = s.physics.supportRadius;
    s.constants.particleMass = s.fluid.particleMass();
    for (std::size_t i = 0; i < points.size(); ++i) {
        s.fluid.position()[i] = points[i];
        s.fluid.density()[i] = s.physics.rho0;
        s.fluid.id()[i] = Index(i);
    }
    const Scalar margin = 4 * s.physics.supportRadius;
    Vec3 dlo = lo - Vec3::Constant(margin), dhi = hi + Vec3::Constant(margin);
    if (dim == 2) dlo[2] = dhi[2] = 0;
    s.search.setup(s.physics.supportRadius, dim, dlo, dhi);
    s.search.build(s.fluid.position());
}

WallSystem& addWallSystem(Scene& s, const std::string& name, const std::vector<Vec3>& positions) {
    WallSystem& w = s.walls.emplace_back(name);
    w.particles.resize(positions.size());
    for (std::size_t b = 0; b < positions.size(); ++b) {
        w.particles.position()[b] = positions[b];
        w.particles.density()[b] = s.physics.rho0;
        w.particles.id()[b] = Index(b);
    }
    std::vector<NeighbourSearch::WallSource> sources;
    for (auto& wall : s.walls) sources.push_back({&wall.particles.position(), wall.moving()});
    s.search.setWalls(sources);
    return w;
}

void setWallMasses(Scene& s, Scalar mass) {
    static std::vector<std::unique_ptr<std::vector<Scalar>>> keep; // outlives the scene's pointers
    for (auto& w : s.walls) {
        keep.push_back(std::make_unique<std::vector<Scalar>>(w.size(), mass));
        w.mass = keep.back().get();
        w.pressureMirrored = true;
    }
}

BlockScene::BlockScene(int dim, const std::string& kernelName, double supportFactor) {
    s.physics = physicsFor(dim, 0.01, supportFactor);
    kernel = createModel<Kernel>("type " + kernelName + ";", s.physics);
}

Vec3 BlockScene::block(int n, double scale) {
    const double dx = s.physics.particleSpacing;
    const Vec3 hi(n * dx, n * dx, s.physics.dimension == 3 ? n * dx : 0);
    fillLattice(s, *kernel, Vec3::Zero(), hi);
    const Vec3 c = 0.5 * hi;
    for (auto& x : s.fluid.position()) x = c + scale * (x - c);
    s.search.build(s.fluid.position());
    return c;
}

void BlockScene::advance(PressureModel& p, double dt) {
    auto& x = s.fluid.position();
    auto& v = s.fluid.velocity();
    for (std::size_t i = 0; i < x.size(); ++i) {
        v[i] += dt * s.fluid.acceleration()[i];
        x[i] += dt * v[i];
    }
    s.search.build(x);
    p.computeDensity(s);
}

double BlockScene::maxCompression() const {
    double e = 0;
    for (auto rho : s.fluid.density()) e = std::max<double>(e, (rho - s.physics.rho0) / s.physics.rho0);
    return e;
}

} // namespace spindrift::test
