// pereaCordero viscosity (plugins/viscosity/pereaCordero; Perea & Cordero, seed 000, eqs. 17–18)
// and xsph (plugins/viscosity/xsph): momentum conservation of the symmetric forms, Galilean
// invariance (a uniformly translating block), consistency with ν∇²v, the damping factor Γ,
// and XSPH's velocity change against a hand computation. The paper's printed form is shown to
// fail both conservation and Galilean invariance.
#include "PairLoop.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <random>

using namespace spindrift;

namespace {

struct TestScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::unique_ptr<PressureModel> density;
    TestScene(int dim, const std::string& kernelName, double nu = 1e-3, double supportRatio = 2.6) {
        s.physics = test::physicsFor(dim, 0.01, supportRatio);
        s.physics.nu = nu;
        kernel = test::createModel<Kernel>("type " + kernelName + ";", s.physics);
        density = test::createModel<PressureModel>("type wcsph; soundSpeed 20;", s.physics);
    }
    // n^dim lattice block jittered by 'jitter'·dx with random velocities of size 'speed'
    void block(int n, double jitter, double speed, unsigned seed = 5) {
        const double dx = s.physics.particleSpacing;
        const int dim = s.physics.dimension;
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(n * dx, n * dx, dim == 3 ? n * dx : 0));
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-1, 1);
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            test::fluidOf(s).particles.position()[i] += jitter * dx * Vec3(u(rng), u(rng), dim == 3 ? u(rng) : 0);
            test::fluidOf(s).particles.velocity()[i] = speed * Vec3(u(rng), u(rng), dim == 3 ? u(rng) : 0);
        }
        test::rebuild(s);
        density->computeDensity(s, test::fluidOf(s), test::stepOf(s));
    }
    const std::vector<Vec3>& accelerate(const std::string& dict, double dt = 1e-4) {
        auto v = test::createModel<ViscosityModel>(dict, s.physics);
        v->initialise(s);
        for (auto& a : test::fluidOf(s).particles.acceleration()) a.setZero();
        v->addAcceleration(s, test::fluidOf(s), test::stepOf(s, dt));
        return test::fluidOf(s).particles.acceleration();
    }
    // |Σ m a| / Σ m |a|
    double netForce() const {
        Vec3 f = Vec3::Zero();
        double total = 0;
        for (const auto& a : test::fluidOf(s).particles.acceleration()) {
            f += a;
            total += a.norm();
        }
        return total > 0 ? f.norm() / total : 0.0;
    }
    double maxAcceleration() const {
        double m = 0;
        for (const auto& a : test::fluidOf(s).particles.acceleration()) m = std::max<double>(m, a.norm());
        return m;
    }
};

const std::vector<std::string> kernels = {"sinc2", "poly6Spiky", "cubicSpline"};

TEST(PereaCorderoViscosity, DifferenceFormAndXsphConserveMomentumThePaperFormDoesNot) {
    for (int dim : {2, 3})
        for (const auto& k : kernels) {
            TestScene sc(dim, k);
            sc.block(dim == 2 ? 16 : 8, 0.1, 1.0);
            sc.accelerate("type pereaCordero; dampingScale 0.5;");
            EXPECT_GT(sc.maxAcceleration(), 0.0);
            // float: the round-off of ~30-term pair sums, relative to the sum of |force|
            EXPECT_LT(sc.netForce(), test::tol(1e-12, 32 * test::eps)) << "difference form, " << k << " " << dim << "D";
            sc.accelerate("type xsph;");
            EXPECT_GT(sc.maxAcceleration(), 0.0);
            EXPECT_LT(sc.netForce(), test::tol(1e-12, 32 * test::eps)) << "xsph, " << k << " " << dim << "D";
            // eq. 17 as printed: the pair's forces are equal, not opposite
            sc.accelerate("type pereaCordero; form paper; dampingScale 0.5;");
            const double paper = sc.netForce();
            if (dim == 2 && k == "sinc2")
                std::cout << "form paper: net force / sum |force| = " << paper << " (random velocities, " << k << ")\n";
            EXPECT_GT(paper, 1e-3) << "form paper, " << k << " " << dim << "D";
        }
}

TEST(PereaCorderoViscosity, UniformTranslationFeelsNoForceInTheDifferenceForm) {
    for (int dim : {2, 3})
        for (const auto& k : kernels) {
            TestScene sc(dim, k);
            sc.block(dim == 2 ? 12 : 7, 0.1, 0.0);
            for (auto& v : test::fluidOf(sc.s).particles.velocity()) v = Vec3(1.5, -0.5, dim == 3 ? 0.7 : 0.0);
            sc.accelerate("type pereaCordero; dampingScale 0.5;");
            EXPECT_EQ(sc.maxAcceleration(), 0.0) << "difference form, " << k << " " << dim << "D";
            sc.accelerate("type xsph;");
            EXPECT_EQ(sc.maxAcceleration(), 0.0) << "xsph, " << k << " " << dim << "D";
            // documents the printed form: a block moving at 1.58 m/s is accelerated (Σ_j m_j ∇²W_ij
            // does not vanish: the missing self term and the free surface)
            sc.accelerate("type pereaCordero; form paper; dampingScale 0.5;");
            if (dim == 2) std::cout << "form paper, uniform translation at 1.58 m/s, " << k << ": max |a| = " << sc.maxAcceleration() << " m/s^2\n";
            EXPECT_GT(sc.maxAcceleration(), 0.01) << "form paper, " << k << " " << dim << "D";
        }
}

// a_x / (ν∇²v)_x at the centre of a regular lattice for v = (c y², 0, 0) (Γ ≈ 1)
double laplacianFactor(int dim, const std::string& kernel, double supportRatio) {
    const double c = 3.0, nu = 1e-3;
    TestScene sc(dim, kernel, nu, supportRatio);
    const int n = dim == 2 ? 16 : 11;
    sc.block(n, 0.0, 0.0);
    const Vec3 centre = Vec3::Constant(n * 0.01 / 2 + 0.005);
    for (std::size_t i = 0; i < test::fluidOf(sc.s).particles.size(); ++i) {
        const double y = test::fluidOf(sc.s).particles.position()[i].y() - centre.y();
        test::fluidOf(sc.s).particles.velocity()[i] = Vec3(c * y * y, 0, 0);
    }
    const auto& a = sc.accelerate("type pereaCordero; dampingScale 1e12;");
    std::size_t best = 0;
    for (std::size_t i = 0; i < test::fluidOf(sc.s).particles.size(); ++i)
        if ((test::fluidOf(sc.s).particles.position()[i] - centre).norm() < (test::fluidOf(sc.s).particles.position()[best] - centre).norm()) best = i;
    EXPECT_LT(std::abs(a[best].y()), 1e-9 * 2 * c * nu);
    return a[best].x() / (2 * c * nu);
}

TEST(PereaCorderoViscosity, DifferenceFormApproximatesNuLaplacianOfV) {
    // The laplacians of cubicSpline and of Müller's viscosity kernel (poly6Spiky) are
    // continuous at the support radius, so the lattice sum converges to ν∇²v as h/Δx grows:
    // at h = 4Δx the difference form carries the physical viscosity once (the ½ is right).
    for (int dim : {2, 3})
        for (const std::string k : {"poly6Spiky", "cubicSpline"}) {
            const double f = laplacianFactor(dim, k, 4.0);
            std::cout << k << " " << dim << "D, h = 4 dx: a / (nu lap v) = " << f << "\n";
            EXPECT_NEAR(f, 1.0, 0.05) << k << " " << dim << "D";
        }
    // sinc2's ∇²W jumps at the support radius (W''(h) = 2A0/h² ≠ 0: the kernel is C¹ there, not
    // C∞), so on a lattice its viscous sum swings with h/Δx (2D: 0.61 at h = 2Δx, the paper's
    // scene, where the neighbours at r = h are counted or not by round-off — 0.29 without them;
    // 1.03 at 2.6Δx, 0.73 at 3Δx, 0.86 at 4Δx); reported, and held to that range.
    for (double ratio : {2.0, 2.6, 3.0, 4.0}) {
        const double f = laplacianFactor(2, "sinc2", ratio);
        std::cout << "sinc2 2D, h = " << ratio << " dx: a / (nu lap v) = " << f << "\n";
        EXPECT_GT(f, 0.2);
        EXPECT_LT(f, 1.6);
    }
}

// The shortest lattice mode, v alternating in sign between nearest neighbours (a checkerboard),
// at the paper's support h = 2Δx: its nearest neighbours sit at q = 1/2, where sinc2's ∇²W is
// negative, so the ∇²W viscous term feeds the mode instead of damping it (growth rate
// ≈ 3.9 ν/h² by a lattice analysis: ~100/s for μ = 2.6 Pa s, h = 0.01 m). Müller's viscosity
// kernel (∇²W ≥ 0) and the cubic spline damp it. One reason why tutorials/pereaWave needs more
// viscosity than the paper's to stay stable (its README).
TEST(PereaCorderoViscosity, CheckerboardModeAtTwiceTheSpacing) {
    for (const std::string k : {"sinc2", "poly6Spiky", "cubicSpline"}) {
        TestScene sc(2, k, 1e-3, 2.0);
        const int n = 12;
        sc.block(n, 0.0, 0.0);
        const double dx = sc.s.physics.particleSpacing;
        for (std::size_t i = 0; i < test::fluidOf(sc.s).particles.size(); ++i) {
            const Vec3& x = test::fluidOf(sc.s).particles.position()[i];
            const long cx = std::lround(x.x() / dx - 0.5), cy = std::lround(x.y() / dx - 0.5);
            test::fluidOf(sc.s).particles.velocity()[i] = Vec3((cx + cy) % 2 == 0 ? 1.0 : -1.0, 0, 0);
        }
        const auto& a = sc.accelerate("type pereaCordero; dampingScale 1e12;");
        double power = 0; // Σ v·a over particles with a full neighbourhood
        for (std::size_t i = 0; i < a.size(); ++i) {
            const Vec3& x = test::fluidOf(sc.s).particles.position()[i];
            if (x.x() > 3 * dx && x.x() < (n - 3) * dx && x.y() > 3 * dx && x.y() < (n - 3) * dx)
                power += test::fluidOf(sc.s).particles.velocity()[i].dot(a[i]);
        }
        std::cout << k << ", h = 2 dx, checkerboard mode: sum v.a = " << power << (power > 0 ? " (grows)" : " (damped)") << "\n";
        if (k == "sinc2") EXPECT_GT(power, 0.0);
        else EXPECT_LT(power, 0.0);
    }
}

TEST(PereaCorderoViscosity, DampingFactorGammaAgainstAHandComputation) {
    // two particles: a_0 = m ½(μ/ρ0² + μ/ρ1²)(v1 − v0) ∇²W(r) Γ,
    // Γ = exp(−2 |v1 − v0| / (U (ρ0 ρ1/ρ_ref²) (r/h)))
    TestScene sc(2, "sinc2");
    test::fillLattice(sc.s, *sc.kernel, Vec3::Zero(), Vec3(0.02, 0.01, 0));
    const double r = 0.013, h = sc.s.constants.supportRadius, rhoRef = sc.s.physics.rho0, m = test::fluidOf(sc.s).particles.particleMass();
    test::fluidOf(sc.s).particles.position() = {Vec3(0, 0, 0), Vec3(r * 0.6, r * 0.8, 0)};
    test::fluidOf(sc.s).particles.velocity() = {Vec3(0.1, 0, 0), Vec3(-0.05, 0.2, 0)};
    test::fluidOf(sc.s).particles.density() = {1003, 995};
    test::rebuild(sc.s);
    const double mu = 0.26, rho0 = 1003, rho1 = 995;
    const Vec3 dv = test::fluidOf(sc.s).particles.velocity()[1] - test::fluidOf(sc.s).particles.velocity()[0];
    for (double U : {0.05, 0.5, 5.0}) {
        const auto& a = sc.accelerate("type pereaCordero; mu 0.26; dampingScale " + std::to_string(U) + ";");
        const double gamma = std::exp(-2 * dv.norm() / (U * (rho0 * rho1 / (rhoRef * rhoRef)) * (r / h)));
        const Vec3 expected = m * 0.5 * (mu / (rho0 * rho0) + mu / (rho1 * rho1)) * sc.kernel->laplacian(r) * gamma * dv;
        EXPECT_LT((a[0] - expected).norm(), 1e-5 * expected.norm()) << "U = " << U << ", Gamma = " << gamma;
        EXPECT_LT(gamma, 1.0);
    }
    // the default scale U = h² ρ_ref² reproduces eq. 18 as printed, in SI units
    const auto& a = sc.accelerate("type pereaCordero; mu 0.26;");
    const double gammaPrinted = std::exp(-2 * dv.norm() / (h * rho0 * rho1 * r));
    const Vec3 expected = m * 0.5 * (mu / (rho0 * rho0) + mu / (rho1 * rho1)) * sc.kernel->laplacian(r) * gammaPrinted * dv;
    EXPECT_LT((a[0] - expected).norm(), 1e-5 * expected.norm());
    EXPECT_GT(gammaPrinted, 0.99) << "as printed, Gamma is about 1 for water in SI units";
    // form paper: a_0 = m (μ v1/ρ1² + μ v0/ρ0²) ∇²W Γ
    const auto& b = sc.accelerate("type pereaCordero; form paper; mu 0.26; dampingScale 0.5;");
    const double gamma = std::exp(-2 * dv.norm() / (0.5 * (rho0 * rho1 / (rhoRef * rhoRef)) * (r / h)));
    const Vec3 paper = m * (mu * test::fluidOf(sc.s).particles.velocity()[1] / (rho1 * rho1) + mu * test::fluidOf(sc.s).particles.velocity()[0] / (rho0 * rho0)) *
                       sc.kernel->laplacian(r) * gamma;
    EXPECT_LT((b[0] - paper).norm(), 1e-5 * paper.norm());
}

TEST(PereaCorderoViscosity, DissipatesWithThePositiveViscosityKernelLaplacian) {
    // with poly6Spiky the laplacian is Müller's viscosity kernel's (≥ 0): every pair dissipates
    TestScene sc(2, "poly6Spiky");
    sc.block(14, 0.1, 1.0);
    const auto& a = sc.accelerate("type pereaCordero; dampingScale 0.5;");
    double power = 0;
    for (std::size_t i = 0; i < a.size(); ++i) power += test::fluidOf(sc.s).particles.velocity()[i].dot(a[i]);
    EXPECT_LT(power, 0.0);
}

TEST(PereaCorderoViscosity, OptionsAndErrors) {
    auto physics = test::physicsFor(2);
    physics.nu = 0;
    EXPECT_THROW(test::createModel<ViscosityModel>("type pereaCordero;", physics), InputError); // no viscosity
    EXPECT_NO_THROW(test::createModel<ViscosityModel>("type pereaCordero; mu 0.26;", physics));
    EXPECT_THROW(test::createModel<ViscosityModel>("type pereaCordero; mu 0.26; form sum;", physics), InputError);
    EXPECT_THROW(test::createModel<ViscosityModel>("type pereaCordero; mu 0.26; dampingScale 0;", physics), InputError);
    auto v = test::createModel<ViscosityModel>("type pereaCordero; mu 0.26;", physics);
    // the viscous step limit of ν = μ/ρ0: 0.125 (h/2)² / ν
    Scene s;
    s.constants = test::constantsFor(physics);
    const double h = s.constants.supportRadius, limit = 0.125 * 0.25 * h * h / (0.26 / physics.rho0);
    EXPECT_NEAR(v->maxTimeStep(s, StateSpeeds{}), limit, test::tol(1e-12, 1e-5) * limit);
}

TEST(PereaCorderoViscosity, WallFrictionDoesNotGrowWithTheDensityDeficit) {
    // tutorials/pereaWave (issue 34): a lone particle beside a wall sums 0.33-0.45 ρ0 (its
    // neighbourhood is half wall, half empty), and μ/ρ_i² made the wall's no-slip friction
    // (ρ0/ρ_i)² ≈ 5.5 times the bulk's: it held particles on the wall at 0.03 m/s. The wall term
    // takes ρ_i at least ρ0 (wallDensityFloor, default); a compressed particle keeps μ/ρ_i².
    TestScene sc(2, "sinc2", 1e-3, 2.0);
    const double dx = sc.s.physics.particleSpacing;
    test::fillLattice(sc.s, *sc.kernel, Vec3::Zero(), Vec3(dx, dx, 0));
    std::vector<Vec3> wall; // three layers left of x = 0, on the fluid's lattice
    for (int layer = 0; layer < 3; ++layer)
        for (int j = -4; j <= 4; ++j) wall.emplace_back(-(layer + 0.5) * dx, j * dx, 0);
    test::addWallSystem(sc.s, "wall", wall);
    auto& fluid = test::fluidOf(sc.s);
    ASSERT_EQ(fluid.particles.size(), 1u);
    fluid.particles.position() = {Vec3(0.75 * dx, 0, 0)};
    fluid.particles.velocity() = {Vec3(0, -0.3, 0)};
    test::rebuild(sc.s);
    auto akinci = test::createModel<BoundaryModel>("type akinci; volume lattice;", sc.s.physics);
    akinci->initialise(sc.s);
    const double rho0 = sc.s.physics.rho0;
    auto friction = [&](double rho, const std::string& options) {
        fluid.particles.density() = {rho};
        return Vec3(sc.accelerate("type pereaCordero; mu 2.6; dampingScale 1e9; " + options)[0]); // Γ = 1
    };
    const Vec3 atRest = friction(rho0, "");
    ASSERT_GT(atRest.y(), 0.0) << "the wall drags the particle back: it slides down, the friction points up";
    for (double deficit : {0.43, 0.7, 0.99}) {
        const Vec3 a = friction(deficit * rho0, "");
        EXPECT_LT((a - atRest).norm(), 1e-6 * atRest.norm()) << "rho = " << deficit << " rho0";
        const Vec3 unfloored = friction(deficit * rho0, "wallDensityFloor no;");
        EXPECT_NEAR(unfloored.y(), atRest.y() / (deficit * deficit), 1e-6 * unfloored.norm()) << "rho = " << deficit << " rho0";
    }
    const Vec3 compressed = friction(1.05 * rho0, "");
    EXPECT_NEAR(compressed.y(), atRest.y() / (1.05 * 1.05), 1e-6 * atRest.norm());
}

TEST(Xsph, VelocityChangeOverAStepMatchesAHandComputation) {
    // Δv_i = dt a_i = c Σ_j (2 m / (ρ_i + ρ_j)) (v_j − v_i) W_ij, and kinetic energy decreases
    TestScene sc(2, "cubicSpline");
    sc.block(12, 0.1, 1.0);
    const double dt = 2e-4, c = 0.05;
    const auto& a = sc.accelerate("type xsph; c 0.05;", dt);
    const auto& x = test::fluidOf(sc.s).particles.position();
    const auto& v = test::fluidOf(sc.s).particles.velocity();
    const auto& rho = test::fluidOf(sc.s).particles.density();
    const double m = test::fluidOf(sc.s).particles.particleMass(), h = sc.s.constants.supportRadius;
    double power = 0, worst = 0, scale = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        Vec3 dv = Vec3::Zero();
        for (std::size_t j = 0; j < x.size(); ++j) {
            const double r = (x[i] - x[j]).norm();
            if (j != i && r < h) dv += c * 2 * m / (rho[i] + rho[j]) * sc.kernel->W(r) * (v[j] - v[i]);
        }
        worst = std::max<double>(worst, (dt * a[i] - dv).norm());
        scale = std::max<double>(scale, dv.norm());
        power += v[i].dot(a[i]);
    }
    EXPECT_LT(worst, 1e-5 * scale);
    EXPECT_LT(power, 0.0);
    EXPECT_THROW(test::createModel<ViscosityModel>("type xsph; c 2;", sc.s.physics), InputError);
}

} // namespace
