// Spindrift — micro-benchmarks of one step's parts on a 3D block of water (a lattice with a
// small jitter, neighbours as in a run), at about 10k and 100k particles: neighbour search,
// space-filling-curve order, density pass, pressure force pass, one PCISPH iteration, one
// integrator step, and the viscosity pass (to show what a case without viscosity saves).
#include "Log.hpp"
#include "ModelRegistry.hpp"
#include "Simulation.hpp"
#include "PairLoop.hpp"

#include <benchmark/benchmark.h>
#include <algorithm>
#include <random>

using namespace spindrift;

namespace {

struct BenchScene {
    Scene s;
    ParticleSystem* fluid = nullptr;
    std::unique_ptr<Kernel> kernel;
    std::vector<std::unique_ptr<Dictionary>> dicts;
    CoreServices core;

    template <class Base> std::unique_ptr<Base> make(const std::string& text, const std::string& solution = "") {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(text, "bench")));
        const Dictionary* sol = nullptr;
        if (!solution.empty()) {
            dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(solution, "bench")));
            sol = dicts.back().get();
        }
        return ModelRegistry::instance().create<Base>(*dicts[dicts.size() - (sol ? 2 : 1)], s.physics, s.constants, sol);
    }
    Step step(Scalar dt) const { return {s.time, dt, core}; }

    explicit BenchScene(int side) {
        log::setQuiet(true);
        s.physics.dimension = 3;
        s.physics.rho0 = 1000;
        s.physics.particleSpacing = 0.01;
        s.physics.supportRadiusFactor = 2; // h = 0.02 (4r), as the speed reference
        s.physics.gravity = Vec3(0, -9.81, 0);
        s.constants.supportRadius = 0.02;
        s.constants.rho0 = 1000;
        kernel = make<Kernel>("type cubicSpline;");
        s.kernel.build(*kernel);
        std::mt19937 rng(1);
        std::uniform_real_distribution<Scalar> jitter(-0.05, 0.05);
        const Scalar dx = s.physics.particleSpacing;
        fluid = &s.addSystem("fluid", SystemRole::fluid);
        fluid->rho0 = 1000;
        auto& set = fluid->particles;
        set.resize(std::size_t(side) * side * side);
        set.setParticleMass(latticeParticleMass(s.kernel, s.physics));
        s.constants.particleMass = set.particleMass();
        std::size_t n = 0;
        for (int k = 0; k < side; ++k)
            for (int j = 0; j < side; ++j)
                for (int i = 0; i < side; ++i, ++n) {
                    set.position()[n] = Vec3((i + 0.5 + jitter(rng)) * dx, (j + 0.5 + jitter(rng)) * dx,
                                             (k + 0.5 + jitter(rng)) * dx);
                    set.id()[n] = Index(n);
                }
        const Scalar L = side * dx;
        s.search.setup(s.constants.supportRadius, 3, Vec3::Constant(-0.1 * L), Vec3::Constant(1.1 * L));
        s.registerWithSearch(*fluid);
        set.permute(s.search.sortOrder(set.position()));
        s.search.build();
    }
};

int sideFor(benchmark::State& state) { return int(state.range(0)); }
void report(benchmark::State& state, const BenchScene& scene) {
    const double n = double(scene.fluid->size());
    state.counters["particles"] = n;
    state.counters["us/particle"] =
        benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["neighbours"] = double(scene.s.listsOf(*scene.fluid).own().totalPairs()) / n;
}

void NeighbourSearchBuild(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    for (auto _ : state) {
        scene.s.search.positionsChanged(scene.fluid->index);
        scene.s.search.build();
    }
    report(state, scene);
}

// The order of the space-filling-curve re-sort (every few steps), on positions moved since
// the last one.
void SpaceFillingCurveOrder(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    std::vector<Vec3> moved = scene.fluid->particles.position();
    std::mt19937 rng(2);
    std::uniform_real_distribution<Scalar> step(-0.2, 0.2);
    for (Vec3& x : moved) x += scene.s.physics.particleSpacing * Vec3(step(rng), step(rng), step(rng));
    for (auto _ : state) benchmark::DoNotOptimize(scene.s.search.sortOrder(moved));
    report(state, scene);
}

void DensityPass(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    auto& set = scene.fluid->particles;
    for (auto _ : state) summationDensity(scene.s, *scene.fluid, set.position(), set.density());
    report(state, scene);
}

void WcsphForcePass(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    auto pressure = scene.make<PressureModel>("type wcsph; soundSpeed 20;");
    pressure->initialise(scene.s);
    pressure->computeDensity(scene.s, *scene.fluid, scene.step(1e-4));
    for (auto _ : state) pressure->addPressureAcceleration(scene.s, *scene.fluid, scene.step(1e-4));
    report(state, scene);
}

void ArtificialViscosityPass(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    scene.s.constants.soundSpeed = 20;
    auto viscosity = scene.make<ViscosityModel>("type artificial;");
    viscosity->initialise(scene.s);
    for (auto _ : state) viscosity->addAcceleration(scene.s, *scene.fluid, scene.step(1e-4));
    report(state, scene);
}

void PcisphOneIteration(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    const auto pressures = ModelRegistry::instance().available("pressure");
    if (std::find(pressures.begin(), pressures.end(), "pcisph") == pressures.end()) {
        state.SkipWithError("pcisph plugin not built");
        return;
    }
    auto pcisph = scene.make<PressureModel>("type pcisph;", "minIterations 1; maxIterations 1;");
    pcisph->initialise(scene.s);
    pcisph->computeDensity(scene.s, *scene.fluid, scene.step(1e-3));
    for (auto _ : state) pcisph->addPressureAcceleration(scene.s, *scene.fluid, scene.step(1e-3));
    report(state, scene);
}

void SymplecticEulerStep(benchmark::State& state) {
    BenchScene scene(sideFor(state));
    auto integrator = scene.make<Integrator>("type symplecticEuler;");
    for (auto _ : state) integrator->step(scene.s, scene.core, 1e-6, [](double, Scalar) {});
    report(state, scene);
}

// 22³ ≈ 10k and 46³ ≈ 100k particles
#define SIZES Arg(22)->Arg(46)->Unit(benchmark::kMillisecond)
BENCHMARK(NeighbourSearchBuild)->SIZES;
BENCHMARK(SpaceFillingCurveOrder)->SIZES;
BENCHMARK(DensityPass)->SIZES;
BENCHMARK(WcsphForcePass)->SIZES;
BENCHMARK(ArtificialViscosityPass)->SIZES;
BENCHMARK(PcisphOneIteration)->SIZES;
BENCHMARK(SymplecticEulerStep)->SIZES;

} // namespace

BENCHMARK_MAIN();
