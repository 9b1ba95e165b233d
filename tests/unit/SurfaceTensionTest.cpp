// Surface tension (plugins/surfaceTension): mueller2003 on droplets at rest, where its figures
// are known: the curvature of a disc (1/R) and a ball (2/R), the force's direction (inwards), its
// total (σ times the curvature times the surface: the delta function integrates to 1 across the
// surface), no net force, nothing on a flat surface; the capillary step limit; bad input.
#include "PairLoop.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace spindrift;

namespace {

constexpr double dx = 0.01, rho0 = 1000, sigma = 0.0728;

// A droplet (below), or a slab of the lattice
// periodic along x (and z) with free surfaces at y = 0 and y = ny dx, models from sphSchemes text.
struct DropScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::vector<std::unique_ptr<Dictionary>> dicts;

    // particles on rings (2D) or shells (3D, Fibonacci points on each) Δx apart, the outer one
    // Δx/2 inside 'radius', each particle carrying about Δx^d: the layout a droplet relaxes to (a
    // lattice disc's staircase turns the normals in steps, which no smooth surface does)
    DropScene(int dim, double radius) {
        s.physics = test::physicsFor(dim, dx, 2.6, rho0);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const Vec3 half = Vec3(radius, radius, dim == 3 ? radius : 0);
        ParticleSystem& f = test::fillLattice(s, *kernel, -half, half); // (the mass, search and constants)
        std::vector<Vec3> points;
        if (dim == 3) points.push_back(Vec3::Zero()); // (in 2D the innermost ring is Δx/2 from the centre)
        const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
        int layer = 0;
        for (double r = radius - 0.5 * dx; r > (dim == 2 ? 0.25 : 0.75) * dx; r -= dx, ++layer) {
            const long n = std::lround(dim == 2 ? 2 * std::numbers::pi * r / dx : 4 * std::numbers::pi * r * r / (dx * dx));
            for (long k = 0; k < n; ++k) {
                if (dim == 2) {
                    const double angle = 2 * std::numbers::pi * (k + 0.5 * layer) / double(n);
                    points.emplace_back(r * std::cos(angle), r * std::sin(angle), 0);
                } else {
                    const double z = 1 - (2 * k + 1) / double(n), rho = std::sqrt(1 - z * z), phi = golden * double(k);
                    points.emplace_back(r * rho * std::cos(phi), r * rho * std::sin(phi), r * z);
                }
            }
        }
        f.particles.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
            f.particles.position()[i] = points[i];
            f.particles.density()[i] = rho0;
            f.particles.id()[i] = Index(i);
        }
        test::rebuild(s);
    }
    DropScene(int nx, int ny, int nz) {
        const int dim = nz > 0 ? 3 : 2;
        s.physics = test::physicsFor(dim, dx, 2.6, rho0);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const Vec3 hi(nx * dx, ny * dx, nz * dx);
        ParticleSystem& f = test::fillLattice(s, *kernel, Vec3::Zero(), hi);
        Periodicity periodic;
        periodic.axis[0] = true;
        periodic.axis[2] = dim == 3;
        periodic.length = hi;
        const Scalar margin = 4 * s.constants.supportRadius;
        s.search.setup(s.constants.supportRadius, dim, Vec3(0, -margin, 0), Vec3(hi[0], hi[1] + margin, hi[2]),
                       periodic);
        s.registerWithSearch(f);
        test::rebuild(s);
    }
    ParticleSystem& fluid() { return test::fluidOf(s); }
    std::unique_ptr<SurfaceTensionModel> model(const std::string& text) {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(text, "sphSchemes.surfaceTension")));
        auto m = ModelRegistry::instance().create<SurfaceTensionModel>(*dicts.back(), s.physics, s.constants);
        m->initialise(s);
        return m;
    }
    // the model's acceleration of every particle (from zero)
    const std::vector<Vec3>& accelerate(SurfaceTensionModel& m) {
        auto& a = fluid().particles.acceleration();
        std::fill(a.begin(), a.end(), Vec3::Zero());
        m.addAcceleration(s, fluid(), test::stepOf(s));
        return a;
    }
};

const std::string mueller = "type mueller2003; sigma 0.0728;";

// The disc and the ball: the total inward force Σ m a·(−x̂) is σ κ times the surface (2πR, 4πR²);
// the net force vanishes; the force points inwards; the outer particles' curvature is (d − 1)/R.
void checkDroplet(int dim, double radius) {
    DropScene sc(dim, radius);
    auto m = sc.model(mueller);
    const auto& a = sc.accelerate(*m);
    const auto& x = sc.fluid().particles.position();
    const auto& kappa = *sc.fluid().particles.findScalar("curvature");
    const double mass = sc.fluid().particles.particleMass();
    const double R = radius;
    Vec3 net = Vec3::Zero();
    double inward = 0, outward = 0, kappaSum = 0, kappaCount = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        net += mass * a[i];
        const double radial = a[i].dot(x[i].normalized());
        (radial < 0 ? inward : outward) += mass * std::abs(radial);
        if (x[i].norm() > R - dx) { // the outer ring or shell
            kappaSum += kappa[i];
            ++kappaCount;
        }
    }
    // the force acts on the outer row of particles, Δx/2 inside the surface: σ (d − 1)/R on the
    // row's length or area balances the Laplace pressure σ (d − 1)/R inside it
    const double row = R - 0.5 * dx;
    const double surface = dim == 2 ? 2 * std::numbers::pi * row : 4 * std::numbers::pi * row * row;
    const double expected = sigma * (dim - 1) / R * surface;
    std::cout << dim << "D droplet of " << x.size() << " particles, R = " << R / dx << " dx: inward force "
              << inward / expected << " of sigma kappa S, outward " << outward / expected << ", outer curvature "
              << kappaSum / kappaCount * R / (dim - 1) << " of (d-1)/R\n";
    // (measured: 0.989 on the disc; 1.059 on the ball, whose shells of Fibonacci points lie less
    // evenly than rings)
    EXPECT_NEAR(inward / expected, 1.0, dim == 2 ? 0.03 : 0.08);
    EXPECT_LT(outward, 0.02 * inward);
    EXPECT_LT(net.norm(), 1e-9 * expected + test::tol(0, 1e-5) * expected);
    EXPECT_NEAR(kappaSum / kappaCount * R / (dim - 1), 1.0, 0.01);
}

TEST(Mueller2003, DiscIsPulledInWithSigmaOverRAndNoNetForce) { checkDroplet(2, 20 * dx); }

TEST(Mueller2003, BallIsPulledInWithTwoSigmaOverR) { checkDroplet(3, 9 * dx); }

TEST(Mueller2003, FlatSurfaceFeelsNothing) {
    for (int nz : {0, 8}) {
        DropScene sc(12, 10, nz);
        auto m = sc.model(mueller);
        const auto& a = sc.accelerate(*m);
        double largest = 0;
        for (const Vec3& ai : a) largest = std::max(largest, double(ai.norm()));
        // the scale: σ κ δ/ρ with κ = 1/h (a droplet of the support's radius), δ = 1/Δx
        const double scale = sigma / (sc.s.constants.supportRadius * dx * rho0);
        EXPECT_LT(largest, test::tol(1e-9, 1e-4) * scale) << (nz ? "3D" : "2D");
    }
}

TEST(Mueller2003, CurvatureIsAllocatedOnlyWithTheModel) {
    DropScene sc(2, 10 * dx);
    EXPECT_EQ(sc.fluid().particles.findScalar("curvature"), nullptr);
    auto m = sc.model(mueller);
    EXPECT_NE(sc.fluid().particles.findScalar("curvature"), nullptr);
}

TEST(SurfaceTension, CapillaryTimeStepLimit) {
    DropScene sc(2, 10 * dx);
    auto m = sc.model(mueller);
    const double limit = std::sqrt(rho0 * dx * dx * dx / (2 * std::numbers::pi * sigma));
    EXPECT_NEAR(m->maxTimeStep(sc.s), limit, test::tol(1e-12, 1e-6) * limit); // (ρ0, Δx are Scalars)
    EXPECT_TRUE(std::isinf(sc.model("type mueller2003; sigma 0;")->maxTimeStep(sc.s)));
}

TEST(SurfaceTension, BadSigmaIsRefusedNamingTheKeyword) {
    DropScene sc(2, 10 * dx);
    for (const std::string& text : {std::string("type mueller2003;"), std::string("type mueller2003; sigma -1;")}) {
        try {
            sc.model(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos) << e.what();
        }
    }
}

} // namespace
