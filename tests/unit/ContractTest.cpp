// Contract tests generated from the registry: every plugin of a kind found on the plugin path
// (ModelRegistry::available) gets its kind's tests, so a new plugin is tested the day it lands,
// without a hand-written list.
//   kernel      (each in 2D and 3D): ∫W dV = 1, W and dW/dr vanish at the support, W decreases,
//               dW/dr and ∇²W against finite differences of W (where gradientIsDerivativeOfW()),
//               the KernelTable against the analytic kernel;
//   viscosity   Σ m a = 0 among fluid particles (no walls), dissipation (Σ m v·a < 0), and
//               Galilean invariance: a uniform velocity added to every particle changes no
//               acceleration;
//   integrator  the global order of accuracy it declares (Integrator::order) on a harmonic
//               oscillator: the error at T = 1 falls by 2^order when Δt is halved; it advances
//               an integrated density once a step through the core, and moves the particles
//               with the core's drift (a shifting model's transport velocity included);
//   pressure    a small 2D water column in a tank (the hydrostaticTank2D tutorial, narrowed
//               and lowered) stays at rest, its density near ρ0 and its bottom-row pressure
//               near ρ0 g (H − z), with each solver's defaults; the bounds are per solver (what
//               each meets today, measured, with margin), a solver not listed gets the default.
#include "Case.hpp"
#include "KernelTable.hpp"
#include "Log.hpp"
#include "Simulation.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <regex>

using namespace spindrift;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> available(const std::string& kind) { return ModelRegistry::instance().available(kind); }

// gtest names: letters, digits and underscores
std::string testName(const std::string& s) {
    std::string n;
    for (char c : s) n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return n;
}

// The generated suites below are empty if the registry finds nothing: the plugins the
// foundation ships must be found for every kind.
TEST(Contract, TheRegistryFindsThePluginsOfEveryKind) {
    const std::map<std::string, std::vector<std::string>> foundation = {
        {"kernel", {"cubicSpline", "wendlandC2"}}, {"viscosity", {"artificial", "laminar"}},
        {"integrator", {"symplecticEuler", "leapfrog"}}, {"pressure", {"wcsph", "pcisph", "iisph"}}};
    for (const auto& [kind, names] : foundation) {
        const auto found = available(kind);
        for (const auto& name : names)
            EXPECT_NE(std::find(found.begin(), found.end(), name), found.end()) << kind << " " << name;
    }
}

// ---------------------------------------------------------------------------------------------
// kernels

struct KernelCase {
    std::string name;
    int dim;
};
void PrintTo(const KernelCase& c, std::ostream* os) { *os << c.name << " " << c.dim << "D"; }

std::vector<KernelCase> kernelCases() {
    std::vector<KernelCase> out;
    for (const auto& name : available("kernel"))
        for (int dim : {2, 3}) out.push_back({name, dim});
    return out;
}

class KernelContract : public testing::TestWithParam<KernelCase> {
protected:
    std::unique_ptr<Kernel> make(double h = 0.026) {
        auto physics = test::physicsFor(GetParam().dim, h / 2.6, 2.6);
        return test::createModel<Kernel>("type " + GetParam().name + ";", physics);
    }
};

TEST_P(KernelContract, IntegratesToOne) {
    for (double h : {0.026, 1.0, 3.5}) {
        auto k = make(h);
        EXPECT_EQ(k->dimension(), GetParam().dim);
        EXPECT_NEAR(k->supportRadius(), h, 1e-6 * h);
        const double integral = test::radialIntegral([&](double r) { return double(k->W(r)); }, h, k->dimension());
        EXPECT_NEAR(integral, 1.0, 1e-6) << "h = " << h;
    }
}

TEST_P(KernelContract, VanishesAtTheSupportAndDecreases) {
    auto k = make();
    const double h = k->supportRadius();
    EXPECT_NEAR(k->W(h), 0.0, 1e-12 * k->W(0));
    EXPECT_EQ(k->W(1.01 * h), 0.0);
    EXPECT_EQ(k->dWdr(1.01 * h), 0.0);
    // W and dW/dr go continuously to zero at the support radius
    double maxSlope = 0;
    for (double q = 0; q < 1; q += 0.001) maxSlope = std::max(maxSlope, std::abs(double(k->dWdr(q * h))));
    EXPECT_NEAR(k->W(h * (1 - 1e-7)), 0.0, 1e-6 * k->W(0));
    EXPECT_NEAR(k->dWdr(h * (1 - 1e-7)), 0.0, 1e-6 * maxSlope);
    // a radial W differentiable at r = 0 has dW/dr(0) = 0 (a gradient that is not W's own may
    // differ there by design: the spiky kernel's, KernelTest)
    if (k->gradientIsDerivativeOfW()) {
        EXPECT_NEAR(k->dWdr(0.0), 0.0, 1e-9 * std::abs(k->W(0)) / h) << "gradient must vanish at r = 0";
    }
    EXPECT_GT(k->W(0), 0.0);
    for (double q = 0.05; q < 1; q += 0.05) EXPECT_LE(k->dWdr(q * h), 0.0) << "W must decrease, q = " << q;
}

TEST_P(KernelContract, GradientMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "its gradient is not W's derivative, by design";
    // float: the step (~∛eps h/2) that balances rounding of W against truncation (worst measured
    // 4.8e-5), the difference taken over the arguments as rounded to Scalar
    const double h = k->supportRadius(), e = test::tol(1e-6, 2e-3) * h;
    double worst = 0, scale = 0;
    for (double q = 0.01; q < 0.995; q += 0.0123) {
        const double r = q * h;
        const Scalar rp = r + e, rm = r - e;
        const double fd = (k->W(rp) - k->W(rm)) / (double(rp) - double(rm));
        worst = std::max(worst, std::abs(fd - k->dWdr(r)));
        scale = std::max<double>(scale, std::abs(k->dWdr(r)));
    }
    EXPECT_LT(worst / scale, test::tol(1e-6, 1e-4));
}

TEST_P(KernelContract, LaplacianMatchesFiniteDifference) {
    auto k = make();
    if (!k->gradientIsDerivativeOfW()) GTEST_SKIP() << "its laplacian is not W's, by design";
    // float: the step (~eps^(1/4) h/3) that balances rounding against truncation (worst measured
    // 2.2e-4), and the three-point formula on the arguments as rounded to Scalar
    const double h = k->supportRadius(), e = test::tol(1e-4, 7e-3) * h;
    const int d = k->dimension();
    double worst = 0, scale = 0;
    for (double q = 0.02; q < 0.99; q += 0.0173) {
        const Scalar r = q * h, rp = r + e, rm = r - e;
        const double ep = double(rp) - r, em = r - double(rm);
        const double second = 2 * ((k->W(rp) - k->W(r)) / ep - (k->W(r) - k->W(rm)) / em) / (ep + em);
        const double lap = second + (d - 1) * k->dWdr(r) / r;
        worst = std::max(worst, std::abs(lap - k->laplacian(r)));
        scale = std::max<double>(scale, std::abs(k->laplacian(r)));
    }
    EXPECT_LT(worst / scale, test::tol(1e-5, 5e-4));
}

// The table reproduces W, dW/dr and ∇²W, and W and dW/dr from r², to 1e-6 relative to the
// largest value of each (the relative error is taken against the maximum because W → 0 at
// the support); in float to 1e-5 (~100 eps: the stored coefficients are rounded to float).
TEST_P(KernelContract, TableMatchesAnalyticKernel) {
    auto k = make();
    KernelTable table(*k);
    table.enableLaplacian();
    const double h = k->supportRadius();
    double errW = 0, errD = 0, errL = 0, maxW = 0, maxD = 0, maxL = 0, errWSq = 0, errDSq = 0, errDamped = 0,
           maxDamped = 0;
    const double eta2 = 0.01 * h * h;
    EXPECT_NEAR(table.eta2(), eta2, 1e-6 * eta2);
    for (int i = 0; i <= 100000; ++i) {
        const double r = h * i / 100000.0 * 0.999999;
        errW = std::max<double>(errW, std::abs(table.W(r) - k->W(r)));
        errD = std::max<double>(errD, std::abs(table.dWdr(r) - k->dWdr(r)));
        errL = std::max<double>(errL, std::abs(table.laplacian(r) - k->laplacian(r)));
        maxW = std::max<double>(maxW, std::abs(k->W(r)));
        maxD = std::max<double>(maxD, std::abs(k->dWdr(r)));
        maxL = std::max<double>(maxL, std::abs(k->laplacian(r)));
        // the squared-distance tables of the pair loops: W(r) and r · (dW/dr / r)
        errWSq = std::max<double>(errWSq, std::abs(table.WSq(r * r) - k->W(r)));
        // (at r = 0 the gradient is zero by definition, whatever dW/dr is there: the spiky kernel)
        if (r > 0) errDSq = std::max<double>(errDSq, std::abs(table.gradFactorSq(r * r) * r - k->dWdr(r)));
        // the viscous and diffusion terms' r · ∇W/(r² + η²) = r² · dampedGradFactorSq(r²)
        if (r > 0) {
            const double exact = r * k->dWdr(r) / (r * r + eta2);
            errDamped = std::max<double>(errDamped, std::abs(table.dampedGradFactorSq(r * r) * r * r - exact));
            maxDamped = std::max<double>(maxDamped, std::abs(exact));
        }
    }
    EXPECT_LT(errDamped / maxDamped, test::tol(1e-6, 1e-5));
    EXPECT_LT(errW / maxW, test::tol(1e-6, 1e-5));
    EXPECT_LT(errD / maxD, test::tol(1e-6, 1e-5));
    EXPECT_LT(errL / maxL, test::tol(1e-6, 1e-5));
    EXPECT_LT(errWSq / maxW, test::tol(1e-6, 1e-5));
    EXPECT_LT(errDSq / maxD, test::tol(1e-6, 1e-5));
    // zero at the support (in float, h·h·(1/ds) may round into the end of the last interval)
    EXPECT_LE(std::abs(table.WSq(h * h)), test::tol(0, 1e-5) * maxW);
    EXPECT_LE(std::abs(table.gradFactorSq(h * h) * h), test::tol(0, 1e-5) * maxD);
    EXPECT_EQ(table.gradFactorSq(0), 0.0);
    EXPECT_EQ(table.W(h), 0.0);
    EXPECT_EQ(table.W(2 * h), 0.0);
    EXPECT_DOUBLE_EQ(table.W0(), k->W(0));
    // gradient direction: points from j to i times dW/dr (< 0): towards j
    const Vec3 rij(0.3 * h, 0.1 * h, 0);
    const Vec3 g = table.gradW(rij);
    EXPECT_LT(g.dot(rij), 0.0);
    EXPECT_EQ(table.gradW(Vec3::Zero()), Vec3::Zero());
    // a diverging run's distances (NaN, infinite, huge) are outside the support, not indices out
    // of range: its pair loops once read the tables at index INT_MIN and the run died of SIGSEGV
    // instead of stopping at the blow-up check
    for (const Scalar bad : {std::numeric_limits<Scalar>::quiet_NaN(), std::numeric_limits<Scalar>::infinity(),
                             Scalar(1e30), std::numeric_limits<Scalar>::max()}) {
        EXPECT_EQ(table.W(bad), 0.0);
        EXPECT_EQ(table.dWdr(bad), 0.0);
        EXPECT_EQ(table.laplacian(bad), 0.0);
        EXPECT_EQ(table.WSq(bad), 0.0);
        EXPECT_EQ(table.gradFactorSq(bad), 0.0);
        EXPECT_EQ(table.dampedGradFactorSq(bad), 0.0);
    }
}

INSTANTIATE_TEST_SUITE_P(EveryKernel, KernelContract, testing::ValuesIn(kernelCases()),
                         [](const auto& info) { return testName(info.param.name) + std::to_string(info.param.dim) + "D"; });

// ---------------------------------------------------------------------------------------------
// viscosities

// A jittered n^dim block of fluid with random velocities (no walls), its density from wcsph,
// ν = 10⁻³ m²/s and c0 = 20 m/s for the models that need them.
struct ViscosityScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    explicit ViscosityScene(int dim, unsigned seed = 7) {
        s.physics = test::physicsFor(dim, 0.01, 2.6);
        s.physics.nu = 1e-3;
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        const int n = dim == 2 ? 16 : 8;
        const double dx = s.physics.particleSpacing;
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(n * dx, n * dx, dim == 3 ? n * dx : 0));
        s.constants.soundSpeed = 20;
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-1, 1);
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
            test::fluidOf(s).particles.position()[i] += 0.1 * dx * Vec3(u(rng), u(rng), dim == 3 ? u(rng) : 0);
            test::fluidOf(s).particles.velocity()[i] = Vec3(u(rng), u(rng), dim == 3 ? u(rng) : 0);
        }
        test::rebuild(s);
        test::createModel<PressureModel>("type wcsph; soundSpeed 20;", s.physics)->computeDensity(s, test::fluidOf(s), test::stepOf(s));
    }
    // the model's accelerations alone, at the current velocities
    std::vector<Vec3> accelerations(ViscosityModel& model, double dt = 1e-4) {
        for (auto& a : test::fluidOf(s).particles.acceleration()) a.setZero();
        model.addAcceleration(s, test::fluidOf(s), test::stepOf(s, Scalar(dt)));
        return test::fluidOf(s).particles.acceleration();
    }
};

class ViscosityContract : public testing::TestWithParam<std::string> {
protected:
    std::unique_ptr<ViscosityModel> make(ViscosityScene& sc) {
        auto v = test::createModel<ViscosityModel>("type " + GetParam() + ";", sc.s.physics);
        v->initialise(sc.s);
        return v;
    }
};

// Σ m a = 0: every pair's forces are equal and opposite (also Δv/Δt of xsph); and the kinetic
// energy falls, Σ m v·a < 0.
TEST_P(ViscosityContract, ConservesMomentumAndDissipatesEnergy) {
    for (int dim : {2, 3}) {
        ViscosityScene sc(dim);
        auto model = make(sc);
        const auto a = sc.accelerations(*model);
        Vec3 total = Vec3::Zero();
        double scale = 0, power = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            total += a[i];
            scale += a[i].norm();
            power += test::fluidOf(sc.s).particles.velocity()[i].dot(a[i]);
        }
        EXPECT_GT(scale, 0.0) << dim << "D";
        // float: the round-off of ~30-term pair sums
        EXPECT_LT(total.norm(), test::tol(1e-12, 32 * test::eps) * scale) << dim << "D";
        EXPECT_LT(power, 0.0) << dim << "D";
    }
}

// The same random flow seen from a frame moving at U: every acceleration the same, to the
// round-off of the velocity differences.
TEST_P(ViscosityContract, GalileanInvariant) {
    for (int dim : {2, 3}) {
        ViscosityScene sc(dim);
        auto model = make(sc);
        const auto a = sc.accelerations(*model);
        const Vec3 U = dim == 2 ? Vec3(1.5, -0.5, 0) : Vec3(1.5, -0.5, 0.8);
        for (auto& v : test::fluidOf(sc.s).particles.velocity()) v += U;
        auto moving = make(sc);
        const auto b = sc.accelerations(*moving);
        double worst = 0, scale = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            worst = std::max<double>(worst, (a[i] - b[i]).norm());
            scale = std::max<double>(scale, a[i].norm());
        }
        EXPECT_GT(scale, 0.0) << dim << "D";
        // float: v_i − v_j of velocities ~2 m/s rounded to float, relative to ~1 m/s differences
        EXPECT_LT(worst, test::tol(1e-12, 64 * test::eps) * scale) << dim << "D";
        // a uniform translation alone feels nothing
        for (auto& v : test::fluidOf(sc.s).particles.velocity()) v = U;
        auto uniform = make(sc);
        for (const auto& c : sc.accelerations(*uniform)) ASSERT_EQ(c, Vec3::Zero()) << dim << "D";
    }
}

INSTANTIATE_TEST_SUITE_P(EveryViscosity, ViscosityContract, testing::ValuesIn(available("viscosity")),
                         [](const auto& info) { return testName(info.param); });

// ---------------------------------------------------------------------------------------------
// integrators

// x'' = −ω² x, x(0) = (1, 0), v(0) = (0, ω): a circle, x(t) = (cos ωt, sin ωt). The position
// and velocity error at T = 1 with step dt.
double oscillatorError(const std::string& integrator, double dt) {
    const double omega = 2.0, T = 1.0;
    Scene s;
    s.physics = test::physicsFor(3);
    test::fluidOf(s).particles.resize(1);
    test::fluidOf(s).particles.position()[0] = Vec3(1, 0, 0);
    test::fluidOf(s).particles.velocity()[0] = Vec3(0, omega, 0);
    auto model = test::createModel<Integrator>("type " + integrator + ";", s.physics);
    model->initialise(s);
    const auto evaluate = [&](double, Scalar) { test::fluidOf(s).particles.acceleration()[0] = -omega * omega * test::fluidOf(s).particles.position()[0]; };
    const long steps = std::lround(T / dt);
    for (long n = 0; n < steps; ++n) model->step(s, test::noServices(), Scalar(dt), evaluate);
    const Vec3 x(std::cos(omega * T), std::sin(omega * T), 0), v(-omega * std::sin(omega * T), omega * std::cos(omega * T), 0);
    return (test::fluidOf(s).particles.position()[0] - x).norm() + (test::fluidOf(s).particles.velocity()[0] - v).norm() / omega;
}

class IntegratorContract : public testing::TestWithParam<std::string> {};

TEST_P(IntegratorContract, ReachesItsOrderOnAHarmonicOscillator) {
    const int order = test::createModel<Integrator>("type " + GetParam() + ";", test::physicsFor(3))->order();
    ASSERT_GE(order, 1) << "the default settings must be consistent";
    // steps of ωΔt = 0.04 to 0.01: asymptotic, and errors well above float round-off
    const double coarse = oscillatorError(GetParam(), 0.02), medium = oscillatorError(GetParam(), 0.01),
                 fine = oscillatorError(GetParam(), 0.005);
    const double first = std::log2(coarse / medium), second = std::log2(medium / fine);
    std::cout << GetParam() << " (declares order " << order << "): errors " << coarse << ", " << medium << ", " << fine
              << "; observed orders " << first << ", " << second << "\n";
    EXPECT_NEAR(first, order, 0.15);
    EXPECT_NEAR(second, order, 0.15);
}

// Services that give the density a known rate and count how often an integrator asks the core
// to advance it, and whose drift is the core's with a shifting model (the fluid's field
// shiftingVelocity is added to the velocity the particles move with).
class RecordingServices final : public StepServices {
public:
    bool boundariesHaveOwnPressure(const Scene&) const override { return false; }
    void updateBoundaryPressure(Scene&, const ParticleSystem&, const std::vector<Scalar>&) const override {}
    void drift(const Scene& s, const ParticleSystem& f, Scalar dt, const std::vector<Vec3>& v, std::vector<Vec3>& x) const override {
        core_.drift(s, f, dt, v, x);
    }
    void wrap(const Scene& s, const ParticleSystem& f, std::vector<Vec3>& x) const override { core_.wrap(s, f, x); }
    bool integratesDensity(const ParticleSystem&) const override { return true; }
    void advanceDensity(Scene&, ParticleSystem& f, Scalar dt) const override {
        for (auto& rho : f.particles.density()) rho += dt * rate;
        ++calls;
    }
    static constexpr Scalar rate = 10; // dρ/dt [kg/m³/s]
    mutable int calls = 0;

private:
    CoreServices core_{CoreServices::Models{nullptr, nullptr, nullptr, true}};
};

// Every integrator advances an integrated density once a step, through the core (with the rate
// the core gives), and moves the particles with the core's drift, shifting velocity included: a
// particle under no force with velocity v and shift δv goes v + δv.
TEST_P(IntegratorContract, AdvancesTheIntegratedDensityAndAppliesTheShiftingVelocity) {
    Scene s;
    s.physics = test::physicsFor(3);
    ParticleSystem& fluid = test::addFluid(s, 2);
    fluid.particles.addVector("shiftingVelocity", {false, true});
    auto model = test::createModel<Integrator>("type " + GetParam() + ";", s.physics);
    model->initialise(s);
    const Vec3 v0(0.5, 0, 0), shift(0, 0.25, 0);
    auto& set = fluid.particles;
    set.position() = {Vec3::Zero(), Vec3(1, 1, 1)};
    set.velocity() = {v0, v0};
    (*set.findVector("shiftingVelocity")) = {shift, shift};
    RecordingServices core;
    const auto evaluate = [&](double, Scalar) {
        for (auto& a : set.acceleration()) a.setZero();
    };
    const int steps = 40;
    const double dt = 0.01;
    for (int n = 0; n < steps; ++n) {
        model->step(s, core, Scalar(dt), evaluate);
        s.time += dt;
        ++s.step;
    }
    EXPECT_EQ(core.calls, steps) << "once a step for the one fluid";
    EXPECT_NEAR(set.density()[0], 1000 + steps * dt * RecordingServices::rate, test::tol(1e-9, 1e-3));
    const Vec3 expected = Vec3(1, 1, 1) + steps * dt * (v0 + shift);
    EXPECT_LT((set.position()[1] - expected).norm(), test::tol(1e-12, 1e-5))
        << "x = (" << set.position()[1].transpose() << "), expected (" << expected.transpose() << ")";
    EXPECT_LT((set.velocity()[1] - v0).norm(), test::tol(1e-12, 1e-6)) << "the shift moves, it does not accelerate";
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, IntegratorContract, testing::ValuesIn(available("integrator")),
                         [](const auto& info) { return testName(info.param); });

// ---------------------------------------------------------------------------------------------
// pressure solvers

// What each solver meets today in the column below (measured at the end times 1 and 2 s, the
// first five also at 3 s; the test runs 1 s; the bounds have margin). A solver not listed gets
// `fallback`, the bounds that the solvers with a right pressure (wcsph, isobaric, pcisph, iisph)
// meet. Next to the floor every solver's pressure is above ρ0 g (H − z): the mirrored Akinci
// wall's discretisation (wcsph 9–11 %, isobaric 10–11 %, iisph 7–8 %, and 10.4 % with iisph
// converged to η = 10⁻⁵); pcisph's is closest (2–5 %). dfsph's p = ρκ next to a wall is about
// twice the physical one (its header: the wall term applied once, as SPlisHSPlasH); pbf's and
// relaxedPbf's p = −ρ0 λ/Δt² (docs/MODELS.md §pbf) is far off (not yet understood: the physics
// owner's), and pbf leaves particles 0.2 Δx beyond the wall's surface. To be tightened as they
// are fixed.
struct HydrostaticBounds {
    double bottom = 0.15;     // |p_bottom − ρ0 g (H − z)| / (ρ0 g H), the bottom row's time average
    double density = 0.01;    // max (ρ − ρ0)/ρ0 at the end
    double rmsSpeed = 0.05;   // [m/s] (sqrt(g H) = 1.2 m/s)
    double aboveSurface = 2;  // the highest particle's height above H, in Δx
    double penetration = 0.1; // the deepest particle beyond the walls' surface, in Δx
};
const HydrostaticBounds fallback;
// (test::tol(double build, float build): the float build's runs differ from the double's, the
// column's residual motion being chaotic; measured there: isobaric 20 %, pbf 276 %, 1.6 %,
// 0.14 m/s, the others within the double build's bounds.)
const std::map<std::string, HydrostaticBounds> knownBounds = {
    {"pcisph", {0.08, 0.01, 0.05, 2, 0.1}},   // measured 2.0–4.6 %, 0.17 %, 0.020 m/s, none in a wall
    {"iisph", {0.12, 0.01, 0.05, 2, 0.1}},    // 7.0–8.2 %, 0.12 %, 0.021 m/s, none
    {"wcsph", {0.14, 0.01, 0.05, 2, 0.1}},    // 9.3–11.1 %, 0.55 %, 0.019 m/s, none
    {"isobaric", {test::tol(0.15, 0.26), 0.01, 0.05, 2, 0.1}}, // 10.1–11.1 %, 0.64 %, 0.023 m/s, none
    {"dfsph", {1.3, 0.01, 0.05, 2, 0.1}},     // 86–101 %, 0.11 %, 0.022 m/s, none
    {"pbf", {test::tol(3.0, 3.5), test::tol(0.02, 0.025), test::tol(0.15, 0.2), 2, 0.3}}, // 160–235 %, 1.0 %, 0.068 m/s, 0.20 dx into a wall
    {"relaxedPbf", {1.5, 0.02, 0.2, 2, 0.1}}, // 113–114 %, 0.6–1.3 %, 0.10–0.12 m/s, 0.03 dx
};

struct ColumnResult {
    double bottomError = 0, maxDensityError = 0, rmsSpeed = 0, maxSpeed = 0, pBottom = 0, pHydrostatic = 0;
    double aboveSurface = 0; // the highest particle above H [Δx]
    double penetration = 0;  // the deepest particle beyond the walls' surface (x = 0, W; y = 0) [Δx]
    long steps = 0;
};

// The hydrostaticTank2D tutorial narrowed and lowered to a column of W × H = 0.1 × 0.15 m
// (150 particles) in a tank of Akinci walls, with the solver's defaults (no sphSolution),
// artificial viscosity α = 0.1, symplectic Euler, for 1 s; then 50 more steps of 1 ms (or the
// stable step, if smaller) over which the bottom row's pressure is averaged (the incompressible
// solvers' pressure fluctuates from step to step).
ColumnResult hydrostaticColumn(const std::string& pressure) {
    const double width = 0.1, H = 0.15;
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "column";
    copyCaseInput(fs::path(SPINDRIFT_SOURCE_DIR) / "tutorials/hydrostaticTank2D", dir);
    std::string geometry = test::readFile(dir / "constant/geometry");
    geometry = std::regex_replace(geometry, std::regex("max     \\(0\\.2 0\\.3 0\\)"), "max     (0.1 0.15 0)");
    geometry = std::regex_replace(geometry, std::regex("max     \\(0\\.2 0\\.4 0\\)"), "max     (0.1 0.25 0)");
    std::ofstream(dir / "constant/geometry") << geometry;
    std::string schemes = test::readFile(dir / "system/sphSchemes");
    schemes = std::regex_replace(schemes, std::regex("\npressure\\s*\\{[^}]*\\}"), "\npressure\n{\n    type " + pressure + ";\n}",
                                 std::regex_constants::format_first_only);
    schemes = std::regex_replace(schemes, std::regex("\nviscosity\\s*\\{[^}]*\\}"),
                                 "\nviscosity\n{\n    type artificial; alpha 0.1; soundSpeed 25;\n}",
                                 std::regex_constants::format_first_only);
    std::ofstream(dir / "system/sphSchemes") << schemes;
    std::string control = test::readFile(dir / "system/controlDict");
    control = std::regex_replace(control, std::regex("\nendTime[^;]*;"), "\nendTime 1;");
    control = std::regex_replace(control, std::regex("\nwriteInterval[^;]*;"), "\nwriteInterval 1;");
    control = std::regex_replace(control, std::regex("\nmaxDeltaT[^;]*;"), "\nmaxDeltaT 2e-3;");
    std::ofstream(dir / "system/controlDict") << control;
    EXPECT_EQ(test::readFile(dir / "constant/geometry").find("0.3 0"), std::string::npos) << "the geometry was not edited";

    Simulation sim(dir);
    ColumnResult out;
    out.steps = sim.run().steps;
    auto& s = sim.scene();
    const double rho0 = s.physics.rho0, g = 9.81, dx = s.physics.particleSpacing;
    sim.evaluate(s.time, Scalar(1e-3));
    const Scalar dt = Scalar(std::min(1e-3, sim.stableDeltaT()));
    double pSum = 0, zSum = 0;
    long count = 0;
    for (int step = 0; step < 50; ++step) {
        auto& x = test::fluidOf(s).particles.position();
        auto& v = test::fluidOf(s).particles.velocity();
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) { // symplectic Euler: every result kind
            v[i] += dt * test::fluidOf(s).particles.acceleration()[i];
            x[i] += dt * v[i];
        }
        s.time += dt;
        sim.evaluate(s.time, dt);
        for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i)
            if (x[i].y() < dx) {
                pSum += test::fluidOf(s).particles.pressure()[i];
                zSum += x[i].y();
                ++count;
            }
    }
    EXPECT_GT(count, 0);
    out.pBottom = pSum / count;
    out.pHydrostatic = rho0 * g * (H - zSum / count);
    out.bottomError = (out.pBottom - out.pHydrostatic) / (rho0 * g * H);
    double v2 = 0, top = 0;
    for (std::size_t i = 0; i < test::fluidOf(s).particles.size(); ++i) {
        const Vec3 x = test::fluidOf(s).particles.position()[i];
        out.penetration = std::max<double>(out.penetration, std::max<double>({-x.x(), x.x() - width, -x.y()}) / dx);
        top = std::max<double>(top, x.y());
        out.maxDensityError = std::max(out.maxDensityError, double(test::fluidOf(s).particles.density()[i] - rho0) / rho0);
        v2 += test::fluidOf(s).particles.velocity()[i].squaredNorm();
        out.maxSpeed = std::max(out.maxSpeed, double(test::fluidOf(s).particles.velocity()[i].norm()));
    }
    out.rmsSpeed = std::sqrt(v2 / test::fluidOf(s).particles.size());
    out.aboveSurface = (top - H) / dx;
    return out;
}

class PressureContract : public testing::TestWithParam<std::string> {};

TEST_P(PressureContract, KeepsAHydrostaticColumnAtRestWithItsPressure) {
    log::setQuiet(true);
    const std::string& name = GetParam();
    const auto known = knownBounds.find(name);
    const HydrostaticBounds bound = known == knownBounds.end() ? fallback : known->second;
    const ColumnResult r = hydrostaticColumn(name);
    std::cout << name << " hydrostatic column: " << r.steps << " steps; bottom row " << r.pBottom << " Pa vs rho0 g (H - z) "
              << r.pHydrostatic << " Pa: error " << 100 * r.bottomError << " % of rho0 g H (bound " << 100 * bound.bottom
              << " %); max density error " << 100 * r.maxDensityError << " % (bound " << 100 * bound.density
              << " %); RMS speed " << r.rmsSpeed << " m/s (bound " << bound.rmsSpeed << "), max " << r.maxSpeed
              << " m/s; highest particle " << r.aboveSurface << " dx above H (bound " << bound.aboveSurface
              << "); deepest into a wall " << r.penetration << " dx (bound " << bound.penetration << ")\n";
    EXPECT_LE(r.penetration, bound.penetration) << "particles beyond the walls";
    EXPECT_LE(std::abs(r.bottomError), bound.bottom);
    EXPECT_LE(r.maxDensityError, bound.density);
    EXPECT_LE(r.rmsSpeed, bound.rmsSpeed);
    EXPECT_LE(r.aboveSurface, bound.aboveSurface);
}

// An iterative solver predicts where the step takes the particles linearly in Δt: it declares
// Δt ≤ maxDisplacement Δx / |v|max (sphSolution, 0.4 by default: Ihmsen et al. 2014's CFL), so no
// particle moves further in a step whatever the kernel's support and maxCo; nothing at rest. |v|max
// is the fluid's largest speed the core measured (StateSpeeds).
TEST_P(PressureContract, AnIterativeSolverKeepsAStepWithinMaxDisplacement) {
    log::setQuiet(true);
    test::BlockScene sc(2, "wendlandC2", 4.0);
    sc.block(8, 1.0);
    const std::string type = "type " + GetParam() + ";";
    if (!sc.model<PressureModel>(type)->isIterative()) GTEST_SKIP() << GetParam() << " is not iterative";
    const double dx = sc.s.physics.particleSpacing;
    EXPECT_EQ(sc.model<PressureModel>(type)->maxTimeStep(sc.s, StateSpeeds{0}), std::numeric_limits<double>::infinity())
        << "at rest";
    EXPECT_NEAR(sc.model<PressureModel>(type)->maxTimeStep(sc.s, StateSpeeds{2}), 0.4 * dx / 2, 1e-12 * dx);
    EXPECT_NEAR(sc.model<PressureModel>(type, "maxDisplacement 0.25;")->maxTimeStep(sc.s, StateSpeeds{2}), 0.25 * dx / 2,
                1e-12 * dx);
    EXPECT_THROW(sc.model<PressureModel>(type, "maxDisplacement 0;"), InputError);
}

INSTANTIATE_TEST_SUITE_P(EveryPressureSolver, PressureContract, testing::ValuesIn(available("pressure")),
                         [](const auto& info) { return testName(info.param); });

} // namespace
