// Density diffusion plugins (molteni, antuono, fourtakas) on a periodic 2D lattice: a uniform
// density has nothing to diffuse, a density spike loses density to its neighbours, and the
// term moves density without creating mass (Σ_i V_i D_i = 0, V_i = m/ρ_i).
#include "DensityDiffusion.hpp"
#include "PairLoop.hpp"
#include "TestSupport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

using namespace spindrift;

namespace {

constexpr double dx = 0.01, rho0 = 1000;
constexpr int n = 16;

struct DiffusionScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::unique_ptr<Dictionary> dict;
    DiffusionScene() {
        s.physics = test::physicsFor(2, dx, 2.6, rho0);
        kernel = test::createModel<Kernel>("type wendlandC2;", s.physics);
        test::fillLattice(s, *kernel, Vec3::Zero(), Vec3(n * dx, n * dx, 0));
        s.constants.soundSpeed = 10;
        s.constants.eosExponent = 7;
        s.constants.rho0 = rho0;
        Periodicity periodic;
        periodic.axis[0] = periodic.axis[1] = true;
        periodic.length = Vec3(n * dx, n * dx, 0);
        const Scalar margin = 4 * s.constants.supportRadius;
        s.search.setup(s.constants.supportRadius, 2, Vec3(-margin, -margin, 0), Vec3(n * dx + margin, n * dx + margin, 0),
                       periodic);
        s.registerWithSearch(test::fluidOf(s));
        test::rebuild(s);
        s.physics.gravity = Vec3::Zero(); // no hydrostatic part: the three forms agree in sign
        test::fluidOf(s).particles.density().assign(test::fluidOf(s).particles.size(), Scalar(rho0));
    }
    std::vector<Scalar> rate(const std::string& type) {
        dict = std::make_unique<Dictionary>(Dictionary::fromString("type " + type + "; delta 0.1;", "sphSchemes.densityDiffusion"));
        auto model = ModelRegistry::instance().create<DensityDiffusion>(*dict, s.physics, s.constants);
        model->initialise(s);
        // the particles are at rest (for the callers that do not move them): the continuity
        // equation's part of the rate is zero, what remains is the diffusion
        std::vector<Scalar> r;
        model->densityRate(s, test::fluidOf(s), r);
        return r;
    }
};

class EveryDensityDiffusion : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryDensityDiffusion, UniformDensityHasNothingToDiffuse) {
    DiffusionScene sc;
    for (Scalar r : sc.rate(GetParam())) EXPECT_NEAR(r, 0, 1e-9 * rho0);
}

TEST_P(EveryDensityDiffusion, ASpikeLosesDensityToItsNeighboursAndNoMassIsMade) {
    DiffusionScene sc;
    const std::size_t spike = (n / 2) * n + n / 2;
    test::fluidOf(sc.s).particles.density()[spike] = Scalar(1.01 * rho0);
    const auto r = sc.rate(GetParam());
    EXPECT_LT(r[spike], 0) << GetParam();
    double gained = 0, volumeWeighted = 0, scale = 0;
    const Scalar m = test::fluidOf(sc.s).particles.particleMass();
    for (std::size_t i = 0; i < r.size(); ++i) {
        if (i != spike) gained += r[i];
        volumeWeighted += m / test::fluidOf(sc.s).particles.density()[i] * r[i];
        scale += std::abs(m / test::fluidOf(sc.s).particles.density()[i] * r[i]);
    }
    EXPECT_GT(gained, 0) << "the neighbours gain density";
    EXPECT_LT(std::abs(volumeWeighted), test::tol(1e-9, 1e-4) * scale) << "sum of V_i D_i";
}

// densityRate() sums the continuity equation and the diffusion in one pass (TwoTerms): with the
// particles moving, it is the continuity equation's rate plus the rate of the same density at rest.
TEST_P(EveryDensityDiffusion, AddsItsTermToTheContinuityEquationInOnePass) {
    DiffusionScene sc;
    auto& rho = test::fluidOf(sc.s).particles.density();
    for (std::size_t i = 0; i < rho.size(); ++i) rho[i] = Scalar(rho0 * (1 + 0.01 * std::sin(0.7 * double(i))));
    const auto atRest = sc.rate(GetParam());
    auto& v = test::fluidOf(sc.s).particles.velocity();
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = Vec3(std::cos(1.3 * double(i)), std::sin(0.4 * double(i)), 0);
    std::vector<Scalar> continuity, moving;
    continuityDensityRate(sc.s, test::fluidOf(sc.s), continuity);
    sc.dict = std::make_unique<Dictionary>(Dictionary::fromString("type " + std::string(GetParam()) + "; delta 0.1;",
                                                                  "sphSchemes.densityDiffusion"));
    auto model = ModelRegistry::instance().create<DensityDiffusion>(*sc.dict, sc.s.physics, sc.s.constants);
    model->initialise(sc.s);
    model->densityRate(sc.s, test::fluidOf(sc.s), moving);
    double scale = 0;
    for (std::size_t i = 0; i < rho.size(); ++i) scale = std::max(scale, std::abs(double(continuity[i])));
    ASSERT_GT(scale, 0);
    for (std::size_t i = 0; i < rho.size(); ++i)
        ASSERT_NEAR(moving[i], continuity[i] + atRest[i], test::tol(1e-12, 1e-5) * scale) << GetParam() << " particle " << i;
}

INSTANTIATE_TEST_SUITE_P(DensityDiffusion, EveryDensityDiffusion, ::testing::Values("molteni", "antuono", "fourtakas"),
                         [](const auto& info) { return std::string(info.param); });

} // namespace
