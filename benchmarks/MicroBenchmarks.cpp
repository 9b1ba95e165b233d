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

struct Scene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::vector<std::unique_ptr<Dictionary>> dicts;

    template <class Base> std::unique_ptr<Base> make(const std::string& text, const std::string& solution = "") {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(text, "bench")));
        const Dictionary* sol = nullptr;
        if (!solution.empty()) {
            dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(solution, "bench")));
            sol = dicts.back().get();
        }
        return ModelRegistry::instance().create<Base>(*dicts[dicts.size() - (sol ? 2 : 1)], s.physics, sol);
    }

    explicit Scene(int side) {
        log::setQuiet(true);
        s.physics.dimension = 3;
        s.physics.rho0 = 1000;
        s.physics.particleSpacing = 0.01;
        s.physics.supportRadius = 0.02; // 4r, as the speed reference
        s.physics.gravity = Vec3(0, -9.81, 0);
        kernel = make<Kernel>("type cubicSpline;");
        s.kernel.build(*kernel);
        std::mt19937 rng(1);
        std::uniform_real_distribution<Scalar> jitter(-0.05, 0.05);
        const Scalar dx = s.physics.particleSpacing;
        s.fluid.resize(std::size_t(side) * side * side);
        s.fluid.setParticleMass(latticeParticleMass(s.kernel, s.physics));
        std::size_t n = 0;
        for (int k = 0; k < side; ++k)
            for (int j = 0; j < side; ++j)
                for (int i = 0; i < side; ++i, ++n) {
                    s.fluid.position()[n] = Vec3((i + 0.5 + jitter(rng)) * dx, (j + 0.5 + jitter(rng)) * dx,
                                                 (k + 0.5 + jitter(rng)) * dx);
                    s.fluid.id()[n] = Index(n);
                }
        const Scalar L = side * dx;
        s.search.setup(s.physics.supportRadius, 3, Vec3::Constant(-0.1 * L), Vec3::Constant(1.1 * L));
        s.fluid.permute(s.search.sortOrder(s.fluid.position()));
        s.search.build(s.fluid.position());
    }
};

int sideFor(benchmark::State& state) { return int(state.range(0)); }
void report(benchmark::State& state, const Scene& scene) {
    state.counters["particles"] = double(scene.s.fluid.size());
    state.counters["us/particle"] = benchmark::Counter(double(scene.s.fluid.size()),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
    state.counters["neighbours"] = double(scene.s.search.fluidNeighbours().totalPairs()) / scene.s.fluid.size();
}

void NeighbourSearchBuild(benchmark::State& state) {
    Scene scene(sideFor(state));
    for (auto _ : state) scene.s.search.build(scene.s.fluid.position());
    report(state, scene);
}

// The order of the space-filling-curve re-sort (every few steps), on positions moved since
// the last one.
void SpaceFillingCurveOrder(benchmark::State& state) {
    Scene scene(sideFor(state));
    std::vector<Vec3> moved = scene.s.fluid.position();
    std::mt19937 rng(2);
    std::uniform_real_distribution<Scalar> step(-0.2, 0.2);
    for (Vec3& x : moved) x += scene.s.physics.particleSpacing * Vec3(step(rng), step(rng), step(rng));
    for (auto _ : state) benchmark::DoNotOptimize(scene.s.search.sortOrder(moved));
    report(state, scene);
}

void DensityPass(benchmark::State& state) {
    Scene scene(sideFor(state));
    for (auto _ : state) summationDensity(scene.s, scene.s.fluid.position(), scene.s.fluid.density());
    report(state, scene);
}

void WcsphForcePass(benchmark::State& state) {
    Scene scene(sideFor(state));
    auto pressure = scene.make<PressureModel>("type wcsph; soundSpeed 20;");
    pressure->initialise(scene.s);
    pressure->computeDensity(scene.s);
    for (auto _ : state) pressure->addPressureAcceleration(scene.s, 1e-4);
    report(state, scene);
}

void ArtificialViscosityPass(benchmark::State& state) {
    Scene scene(sideFor(state));
    scene.s.soundSpeed = 20;
    auto viscosity = scene.make<ViscosityModel>("type artificial;");
    viscosity->initialise(scene.s);
    for (auto _ : state) viscosity->addAcceleration(scene.s, 1e-4);
    report(state, scene);
}

void PcisphOneIteration(benchmark::State& state) {
    Scene scene(sideFor(state));
    const auto pressures = ModelRegistry::instance().available("pressure");
    if (std::find(pressures.begin(), pressures.end(), "pcisph") == pressures.end()) {
        state.SkipWithError("pcisph plugin not built");
        return;
    }
    auto pcisph = scene.make<PressureModel>("type pcisph;", "minIterations 1; maxIterations 1;");
    pcisph->initialise(scene.s);
    pcisph->computeDensity(scene.s);
    for (auto _ : state) pcisph->addPressureAcceleration(scene.s, 1e-3);
    report(state, scene);
}

void SymplecticEulerStep(benchmark::State& state) {
    Scene scene(sideFor(state));
    auto integrator = scene.make<Integrator>("type symplecticEuler;");
    for (auto _ : state) integrator->step(scene.s, 1e-6, [] {});
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
