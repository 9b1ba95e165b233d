// Surface tension (plugins/surfaceTension): mueller2003 on droplets at rest, where its figures
// are known: the curvature of a disc (1/R) and a ball (2/R), the force's direction (inwards), its
// total (σ times the curvature times the surface: the delta function integrates to 1 across the
// surface), no net force, nothing on a flat surface; akinci2013's pressure jump from σ (its γ
// calibrated on a lattice drop, checked here on rings and shells), momentum kept, adhesion and
// its reaction on the wall; the capillary step limit; bad input.
#include "PairLoop.hpp"
#include "Reactions.hpp"
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
    // lattice: the case's lattice points (k + ½)Δx within 'radius' instead
    DropScene(int dim, double radius, bool lattice = false) {
        s.physics = test::physicsFor(dim, dx, 2.6, rho0);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const Vec3 half = Vec3(radius, radius, dim == 3 ? radius : 0);
        ParticleSystem& f = test::fillLattice(s, *kernel, -half, half); // (the mass, search and constants)
        std::vector<Vec3> points;
        const int M = int(std::ceil(radius / dx));
        for (int c = (dim == 3 ? -M : 0); lattice && c < (dim == 3 ? M : 1); ++c)
            for (int b = -M; b < M; ++b)
                for (int a = -M; a < M; ++a) {
                    const Vec3 p((a + 0.5) * dx, (b + 0.5) * dx, dim == 3 ? (c + 0.5) * dx : 0);
                    if (p.norm() < radius) points.push_back(p);
                }
        if (dim == 3 && !lattice) points.push_back(Vec3::Zero()); // (in 2D the innermost ring is Δx/2 from the centre)
        const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
        int layer = 0;
        for (double r = radius - 0.5 * dx; !lattice && r > (dim == 2 ? 0.25 : 0.75) * dx; r -= dx, ++layer) {
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

// akinci2013 on drops of the case's lattice: the mechanical pressure at R/2, the equation of
// state's p(R/2) = ∫ ρ a·(−x̂) dr from R/2 out (Σ_{|x| > R/2} m a·(−x̂)/(Ω |x|^(d−1)), Ω = 2π or 4π)
// plus the cohesion's own pressure inside (the field cohesionPressure, its mean over |x| < R/4,
// where the lattice's is uniform), is Laplace's σ (d − 1)/R (R from the drop's volume) on average over radii. One drop is
// no measure: the cohesion's pressure is 25–70 times σ/R here, and a lattice disc's staircase moves
// the part its surface holds by ±0.5 % of it from one radius to the next.
double akinciTension(int dim, double radius) {
    DropScene sc(dim, radius, true);
    auto m = sc.model("type akinci2013; sigma 0.0728;");
    const auto& a = sc.accelerate(*m);
    const auto& x = sc.fluid().particles.position();
    const auto& cohesion = *sc.fluid().particles.findScalar("cohesionPressure");
    const double mass = sc.fluid().particles.particleMass();
    const double solidAngle = dim == 2 ? 2 * std::numbers::pi : 4 * std::numbers::pi;
    const double R = std::pow(double(x.size()) * std::pow(dx, dim) / (dim == 2 ? std::numbers::pi : 4 * std::numbers::pi / 3),
                              1.0 / dim);
    double p = 0, cohesionSum = 0, count = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double r = x[i].norm();
        if (r > R / 2) p += mass * double(a[i].dot(-x[i] / x[i].norm())) / (solidAngle * std::pow(r, dim - 1));
        if (r < R / 4) {
            cohesionSum += cohesion[i];
            ++count;
        }
    }
    return (p + cohesionSum / count) * R / (dim - 1);
}

void checkAkinciTension(int dim, double from, double to, double tolerance) {
    double sum = 0, low = 1e300, high = -1e300;
    int n = 0;
    for (double R = from; R <= to + 1e-9; R += 0.5, ++n) {
        const double t = akinciTension(dim, R * dx) / sigma;
        sum += t;
        low = std::min(low, t);
        high = std::max(high, t);
    }
    std::cout << dim << "D akinci2013 lattice drops of R = " << from << "-" << to << " dx: tension " << sum / n
              << " of sigma on average (" << low << " to " << high << ")\n";
    EXPECT_NEAR(sum / n, 1.0, 0.02);
    EXPECT_GT(low, 1 - tolerance);
    EXPECT_LT(high, 1 + tolerance);
}

TEST(Akinci2013, LatticeDiscsHoldUpSigmaOverR) { checkAkinciTension(2, 10, 40, 0.05); }

TEST(Akinci2013, LatticeBallsHoldUpTwoSigmaOverR) { checkAkinciTension(3, 8, 14, 0.05); }

// On particles that do not lie on a lattice (rings): no net force, the terms pair-antisymmetric.
TEST(Akinci2013, MomentumIsKept) {
    for (int dim : {2, 3}) {
        DropScene sc(dim, (dim == 2 ? 15 : 7) * dx);
        auto m = sc.model("type akinci2013; sigma 0.0728;");
        const auto& a = sc.accelerate(*m);
        const double mass = sc.fluid().particles.particleMass();
        Vec3 net = Vec3::Zero();
        double scale = 0;
        for (const Vec3& ai : a) {
            net += mass * ai;
            scale += mass * ai.norm();
        }
        EXPECT_GT(scale, 0);
        EXPECT_LT(net.norm(), test::tol(1e-12, 1e-5) * scale) << dim << "D";
    }
}

// adhesion 1: the fluid next to a wall is pulled towards it, by M_b A(r) per unit γ per boundary
// particle, and the wall feels the opposite (the reaction, kind other); adhesion 0: no wall term
TEST(Akinci2013, AdhesionPullsTheFluidToTheWallWhichFeelsTheReaction) {
    DropScene sc(12, 6, 0);
    std::vector<Vec3> floor;
    for (int k = 0; k < 12; ++k)
        for (int row = 1; row <= 3; ++row) floor.emplace_back((k + 0.5) * dx, -(row - 0.5) * dx, 0);
    ParticleSystem& wall = test::addWallSystem(sc.s, "floor", floor);
    test::setWallMasses(sc.s, sc.fluid().particles.particleMass());
    test::rebuild(sc.s);
    auto without = sc.model("type akinci2013; sigma 0.0728;");
    const std::vector<Vec3> a0 = sc.accelerate(*without);
    auto with = sc.model("type akinci2013; sigma 0.0728; adhesion 1;");
    const std::vector<Vec3> a1 = sc.accelerate(*with);
    const double mass = sc.fluid().particles.particleMass();
    const auto& x = sc.fluid().particles.position();
    Vec3 pull = Vec3::Zero();
    for (std::size_t i = 0; i < x.size(); ++i) {
        const Vec3 adhesion = a1[i] - a0[i];
        if (x[i][1] + 0.5 * dx >= sc.s.constants.supportRadius) EXPECT_EQ(adhesion.norm(), 0) << "beyond the support";
        else EXPECT_LT(adhesion[1], 0) << "towards the wall, particle at y = " << x[i][1];
        pull += mass * adhesion;
    }
    EXPECT_LT(std::abs(pull[0]), 1e-6 * std::abs(pull[1])); // periodic along x: straight down
    Reactions r;
    r.want(wall.index);
    r.clear();
    with->addReactions(sc.s, sc.fluid(), test::stepOf(sc.s), r);
    const Vec3 reaction = r.of(wall.index, ForceKind::other).force.cast<Scalar>();
    EXPECT_NEAR(reaction[1], -pull[1], test::tol(1e-9, 1e-4) * std::abs(pull[1]));
    Reactions none;
    none.want(wall.index);
    none.clear();
    without->addReactions(sc.s, sc.fluid(), test::stepOf(sc.s), none);
    EXPECT_EQ(none.of(wall.index, ForceKind::other).force.norm(), 0);
}

TEST(SurfaceTension, CapillaryTimeStepLimit) {
    DropScene sc(2, 10 * dx);
    auto m = sc.model(mueller);
    const double limit = std::sqrt(rho0 * dx * dx * dx / (2 * std::numbers::pi * sigma));
    EXPECT_NEAR(m->maxTimeStep(sc.s, StateSpeeds{}), limit, test::tol(1e-12, 1e-6) * limit); // (ρ0, Δx are Scalars)
    EXPECT_TRUE(std::isinf(sc.model("type mueller2003; sigma 0;")->maxTimeStep(sc.s, StateSpeeds{})));
}

TEST(SurfaceTension, BadSigmaIsRefusedNamingTheKeyword) {
    DropScene sc(2, 10 * dx);
    for (const std::string& text : {std::string("type mueller2003;"), std::string("type mueller2003; sigma -1;"),
                                     std::string("type akinci2013;")}) {
        try {
            sc.model(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos) << e.what();
        }
    }
    try {
        sc.model("type akinci2013; sigma 0.0728; adhesion -1;");
        ADD_FAILURE() << "accepted a negative adhesion";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("adhesion"), std::string::npos) << e.what();
    }
}

} // namespace
