// Integrators (plugins/integrators/*): observed order of accuracy on free fall and a
// harmonic oscillator (log–log slope of the error over 4 step sizes).
#include "TestSupport.hpp"

#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <numbers>

using namespace spindrift;

namespace {

struct Problem {
    std::function<Vec3(const Vec3& x, const Vec3& v)> acceleration;
    std::function<Vec3(double t)> exactPosition;
    Vec3 x0, v0;
};

const Problem freeFall{[](const Vec3&, const Vec3&) { return Vec3(0, -9.81, 0); },
                       [](double t) { return Vec3(0.5 * t, 1.0 + 2.0 * t - 0.5 * 9.81 * t * t, 0); },
                       Vec3(0, 1, 0), Vec3(0.5, 2, 0)};
const double omega = 2.0;
const Problem oscillator{[](const Vec3& x, const Vec3&) { return Vec3(-omega * omega * x); },
                         [](double t) { return Vec3(std::cos(omega * t), std::sin(omega * t) / omega * omega, 0); },
                         Vec3(1, 0, 0), Vec3(0, omega, 0)};

// Position error at t = T after integrating with step dt.
double positionError(const std::string& integratorName, const Problem& p, double dt, double T = 1.0) {
    Scene s;
    s.physics = test::physicsFor(3);
    auto& set = test::addFluid(s, 1).particles;
    set.position()[0] = p.x0;
    set.velocity()[0] = p.v0;
    auto integrator = test::createModel<Integrator>("type " + integratorName + ";", s.physics);
    integrator->initialise(s);
    auto evaluate = [&](double, Scalar) { set.acceleration()[0] = p.acceleration(set.position()[0], set.velocity()[0]); };
    const int steps = int(std::lround(T / dt));
    for (int n = 0; n < steps; ++n) integrator->step(s, test::noServices(), dt, evaluate);
    return (set.position()[0] - p.exactPosition(steps * dt)).norm();
}

double observedOrder(const std::string& name, const Problem& p) {
    std::vector<double> logDt, logErr;
    for (double dt : {0.02, 0.01, 0.005, 0.0025}) {
        logDt.push_back(std::log(dt));
        logErr.push_back(std::log(positionError(name, p, dt)));
    }
    // least-squares slope
    const double n = logDt.size();
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < logDt.size(); ++i) {
        sx += logDt[i]; sy += logErr[i]; sxx += logDt[i] * logDt[i]; sxy += logDt[i] * logErr[i];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(Integrators, SymplecticEulerIsFirstOrder) {
    const double free = observedOrder("symplecticEuler", freeFall);
    const double osc = observedOrder("symplecticEuler", oscillator);
    std::cout << "symplecticEuler observed order: free fall " << free << ", oscillator " << osc << "\n";
    EXPECT_NEAR(free, 1.0, 0.1);
    EXPECT_NEAR(osc, 1.0, 0.1);
}

TEST(Integrators, LeapfrogIsSecondOrder) {
    const double osc = observedOrder("leapfrog", oscillator);
    std::cout << "leapfrog observed order: oscillator " << osc << "\n";
    EXPECT_NEAR(osc, 2.0, 0.1);
    // exact (to round-off) for a constant acceleration (float: 100 steps of values up to ~10)
    EXPECT_LT(positionError("leapfrog", freeFall, 0.01), test::tol(1e-12, 100 * 10 * test::eps));
}

TEST(Integrators, LeapfrogConservesOscillatorEnergyOverLongTimes) {
    // symplectic: the energy error stays bounded over 1000 periods instead of drifting
    Scene s;
    s.physics = test::physicsFor(3);
    auto& set = test::addFluid(s, 1).particles;
    set.position()[0] = oscillator.x0;
    set.velocity()[0] = oscillator.v0;
    auto integrator = test::createModel<Integrator>("type leapfrog;", s.physics);
    auto evaluate = [&](double, Scalar) { set.acceleration()[0] = oscillator.acceleration(set.position()[0], set.velocity()[0]); };
    auto energy = [&] { return 0.5 * set.velocity()[0].squaredNorm() + 0.5 * omega * omega * set.position()[0].squaredNorm(); };
    const double e0 = energy();
    double worst = 0;
    const double dt = 0.05;
    for (int n = 0; n < int(1000 * 2 * std::numbers::pi / omega / dt); ++n) {
        integrator->step(s, test::noServices(), dt, evaluate);
        worst = std::max(worst, std::abs(energy() - e0) / e0);
    }
    EXPECT_LT(worst, 0.01);
}

} // namespace
