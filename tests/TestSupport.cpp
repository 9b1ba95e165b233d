#include "TestSupport.hpp"

#include "Simulation.hpp"

#include <cmath>
#include <cstdlib>
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

std::vector<std::vector<double>> readDataRows(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::vector<double> row;
        for (std::string v; fields >> v;) row.push_back(std::strtod(v.c_str(), nullptr));
        rows.push_back(std::move(row));
    }
    return rows;
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
    p.supportRadiusFactor = supportFactor;
    p.gravity = Vec3::Zero();
    return p;
}

SceneConstants constantsFor(const PhysicalParameters& physics) {
    SceneConstants c;
    c.supportRadius = physics.supportRadiusFactor * physics.particleSpacing;
    c.rho0 = physics.rho0;
    c.particleMass = physics.particleMass();
    return c;
}

ParticleSystem& fillLattice(Scene& s, const Kernel& kernel, const Vec3& lo, const Vec3& hi) {
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
    const bool added = s.ofRole(SystemRole::fluid).empty();
    ParticleSystem& fluid = added ? s.addSystem("fluid", SystemRole::fluid) : fluidOf(s);
    fluid.rho0 = s.physics.rho0;
    auto& set = fluid.particles;
    set.resize(points.size());
    set.setParticleMass(latticeParticleMass(s.kernel, s.physics));
    s.constants.supportRadius = s.kernel.supportRadius();
    s.constants.particleMass = set.particleMass();
    s.constants.rho0 = s.physics.rho0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        set.position()[i] = points[i];
        set.density()[i] = s.physics.rho0;
        set.id()[i] = Index(i);
    }
    if (added) {
        const Scalar margin = 4 * s.constants.supportRadius;
        Vec3 dlo = lo - Vec3::Constant(margin), dhi = hi + Vec3::Constant(margin);
        if (dim == 2) dlo[2] = dhi[2] = 0;
        s.search.setup(s.constants.supportRadius, dim, dlo, dhi);
        s.registerWithSearch(fluid);
    }
    rebuild(s);
    return fluid;
}

ParticleSystem& addFluid(Scene& s, std::size_t n, const std::string& name) {
    ParticleSystem& fluid = s.addSystem(name, SystemRole::fluid);
    fluid.rho0 = s.physics.rho0;
    fluid.particles.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        fluid.particles.density()[i] = s.physics.rho0;
        fluid.particles.id()[i] = Index(i);
    }
    return fluid;
}

ParticleSystem& fluidOf(Scene& s) {
    const auto fluids = s.ofRole(SystemRole::fluid);
    return fluids.empty() ? addFluid(s, 0) : *fluids.front();
}
const ParticleSystem& fluidOf(const Scene& s) { return *s.ofRole(SystemRole::fluid).at(0); }
ParticleSystem& wallOf(Scene& s, std::size_t k) { return *s.boundaries().at(k); }
std::vector<std::reference_wrapper<ParticleSystem>> walls(Scene& s) {
    std::vector<std::reference_wrapper<ParticleSystem>> out;
    for (ParticleSystem* b : s.boundaries()) out.push_back(*b);
    return out;
}
std::vector<std::reference_wrapper<const ParticleSystem>> walls(const Scene& s) {
    std::vector<std::reference_wrapper<const ParticleSystem>> out;
    for (const ParticleSystem* b : s.boundaries()) out.push_back(*b);
    return out;
}

ParticleSystem& addWallSystem(Scene& s, const std::string& name, const std::vector<Vec3>& positions) {
    ParticleSystem& w = s.addSystem(name, SystemRole::wall);
    w.particles.resize(positions.size());
    for (std::size_t b = 0; b < positions.size(); ++b) {
        w.particles.position()[b] = positions[b];
        w.particles.density()[b] = s.physics.rho0;
        w.particles.id()[b] = Index(b);
    }
    s.registerWithSearch(w);
    return w;
}

void setWallMasses(Scene& s, Scalar mass) {
    static std::vector<std::unique_ptr<std::vector<Scalar>>> keep; // outlives the scene's pointers
    for (ParticleSystem* w : s.boundaries()) {
        keep.push_back(std::make_unique<std::vector<Scalar>>(w->size(), mass));
        w->mass = keep.back().get();
        w->pressureMirrored = true;
    }
}

void rebuild(Scene& s) {
    for (std::size_t k = 0; k < s.search.systemCount(); ++k) s.search.positionsChanged(k);
    s.search.build();
}

const CoreServices& noServices() {
    static const CoreServices none;
    return none;
}

Step stepOf(const Scene& s, Scalar dt, const StepServices& core) { return {s.time, dt, core}; }

BlockScene::BlockScene(int dim, const std::string& kernelName, double supportFactor) {
    s.physics = physicsFor(dim, 0.01, supportFactor);
    kernel = createModel<Kernel>("type " + kernelName + ";", s.physics);
}

Vec3 BlockScene::block(int n, double scale) {
    const double dx = s.physics.particleSpacing;
    const Vec3 hi(n * dx, n * dx, s.physics.dimension == 3 ? n * dx : 0);
    fillLattice(s, *kernel, Vec3::Zero(), hi);
    const Vec3 c = 0.5 * hi;
    for (auto& x : fluid().particles.position()) x = c + scale * (x - c);
    rebuild(s);
    return c;
}

void BlockScene::advance(PressureModel& p, double dt) {
    auto& set = fluid().particles;
    auto& x = set.position();
    auto& v = set.velocity();
    for (std::size_t i = 0; i < x.size(); ++i) {
        v[i] += dt * set.acceleration()[i];
        x[i] += dt * v[i];
    }
    rebuild(s);
    p.computeDensity(s, fluid(), step(Scalar(dt)));
}

double BlockScene::maxCompression() const {
    double e = 0;
    for (auto rho : fluidOf(s).particles.density()) e = std::max<double>(e, (rho - s.physics.rho0) / s.physics.rho0);
    return e;
}

} // namespace spindrift::test
