// Spindrift tests — small helpers shared by the unit tests.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace spindrift::test {

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
public:
    explicit TempDir(const std::string& prefix = "spindrift-test");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    // Writes 'text' to path()/relative (creating parent directories) and returns its path.
    std::filesystem::path writeFile(const std::string& relative, const std::string& text) const;

private:
    std::filesystem::path path_;
};

std::string readFile(const std::filesystem::path& file);
// The numbers of a function object's .dat file (postProcessing/<name>/<time>/<file>.dat), a row
// per line; '#' lines (the header) and blank ones are skipped. Empty if the file is missing.
std::vector<std::vector<double>> readDataRows(const std::filesystem::path& file);

// ∫ W dV of a radial function W(r) over [0, h] in 'dim' dimensions: Gauss–Legendre (5 points)
// on 4096 equal intervals, whose nodes include r = h/2 (where piecewise kernels change formula).
double radialIntegral(const std::function<double(double)>& W, double h, int dim);

} // namespace spindrift::test

#include "ModelRegistry.hpp"
#include "PressureModel.hpp"
#include "Step.hpp"

#include <limits>
#include <type_traits>

namespace spindrift::test {

// Precision of the build (Scalar = float with -DSPINDRIFT_PRECISION=float). Tolerances written
// for double keep their value in the double build; tol(d, f) gives f in the float build.
inline constexpr bool singlePrecision = std::is_same_v<Scalar, float>;
inline constexpr double eps = std::numeric_limits<Scalar>::epsilon();
constexpr double tol(double doubleTol, double floatTol) { return singlePrecision ? floatTol : doubleTol; }
// EXPECT_DOUBLE_EQ in the double build, EXPECT_FLOAT_EQ (4 ulps of float) in the float build.
#ifdef SPINDRIFT_SINGLE_PRECISION
#define EXPECT_SCALAR_EQ(a, b) EXPECT_FLOAT_EQ(a, b)
#else
#define EXPECT_SCALAR_EQ(a, b) EXPECT_DOUBLE_EQ(a, b)
#endif

// Physical parameters for model unit tests: spacing dx, support factor·dx, dimension dim.
PhysicalParameters physicsFor(int dim, Scalar dx = 0.01, Scalar supportFactor = 2.6, Scalar rho0 = 1000);
// The constants the core would fix for them before models are made: the support radius
// factor·Δx, ρ0 and the particle mass ρ0 Δx^d (fillLattice replaces it by the lattice mass).
SceneConstants constantsFor(const PhysicalParameters& physics);

// Creates a model of kind Base from dictionary text such as "type cubicSpline;".
template <class Base>
std::unique_ptr<Base> createModel(const std::string& dictText, const PhysicalParameters& physics) {
    static std::vector<std::unique_ptr<Dictionary>> keep; // models may keep references
    static std::vector<std::unique_ptr<SceneConstants>> constants;
    keep.push_back(std::make_unique<Dictionary>(Dictionary::fromString(dictText, "test")));
    constants.push_back(std::make_unique<SceneConstants>(constantsFor(physics)));
    return ModelRegistry::instance().create<Base>(*keep.back(), physics, *constants.back());
}

// Fills the scene's fluid system (adding it, named "fluid", if the scene has none) with
// particles on a lattice of spacing dx in [lo, hi) (cell centres), with the kernel tabulated,
// the lattice particle mass (density ρ0 inside the block), the scene's constants and the
// neighbour search set up over a generous domain and built.
ParticleSystem& fillLattice(Scene& s, const Kernel& kernel, const Vec3& lo, const Vec3& hi);
// Adds a fluid system of n particles (at the origin, density ρ0; not registered with the search).
ParticleSystem& addFluid(Scene& s, std::size_t n, const std::string& name = "fluid");
// The scene's (first) fluid system; an empty one, named "fluid", is added to a scene without.
ParticleSystem& fluidOf(Scene& s);
const ParticleSystem& fluidOf(const Scene& s);
// The k-th boundary system (wall or body) of the scene, and all of them.
ParticleSystem& wallOf(Scene& s, std::size_t k);
std::vector<std::reference_wrapper<ParticleSystem>> walls(Scene& s);
std::vector<std::reference_wrapper<const ParticleSystem>> walls(const Scene& s);

// Adds a fixed wall system of particles at 'positions' (density ρ0) to the scene, registered with
// its neighbour search (which must be set up). Returns the new wall.
ParticleSystem& addWallSystem(Scene& s, const std::string& name, const std::vector<Vec3>& positions);
// Gives every wall of the scene the same particle mass M_b = mass and mirrored pressure, as a
// boundary model does in its initialise().
void setWallMasses(Scene& s, Scalar mass);
// Builds the scene's neighbour lists again at the systems' current positions (whatever changed).
void rebuild(Scene& s);

// The core's services without any model (no boundary model, no density diffusion, no
// shifting), and a Step of them for model calls at the scene's time.
const CoreServices& noServices();
Step stepOf(const Scene& s, Scalar dt = Scalar(1e-4), const StepServices& core = noServices());

// A block of fluid on a lattice for the pressure solvers' tests: n^dim particles of spacing
// 0.01, positions scaled by 'scale' about the block centre (scale < 1: compressed), and models
// made from sphSchemes / sphSolution text (the dictionaries outlive the models).
struct BlockScene {
    Scene s;
    std::unique_ptr<Kernel> kernel;
    std::vector<std::unique_ptr<Dictionary>> dicts;
    CoreServices core; // the services of the models made here (a pressure model: whether it integrates the density)
    BlockScene(int dim, const std::string& kernelName, double supportFactor);
    Vec3 block(int n, double scale); // returns the block centre; neighbour lists built
    ParticleSystem& fluid() { return fluidOf(s); }
    Step step(Scalar dt = Scalar(1e-4)) const { return {s.time, dt, core}; }
    template <class Base> std::unique_ptr<Base> model(const std::string& schemes, const std::string& solution = "") {
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(schemes, "sphSchemes.pressure")));
        const Dictionary& d = *dicts.back();
        dicts.push_back(std::make_unique<Dictionary>(Dictionary::fromString(solution, "sphSolution.pressure")));
        auto m = ModelRegistry::instance().create<Base>(d, s.physics, s.constants, dicts.back().get());
        if constexpr (std::is_same_v<Base, PressureModel>) {
            s.constants.soundSpeed = m->soundSpeed(s.constants, s.physics);
            core.setModels({nullptr, nullptr, m.get(), false});
        }
        m->initialise(s);
        return m;
    }
    // max over the particles of (ρ − ρ0)/ρ0
    double maxCompression() const;
    // symplectic Euler with the accelerations just computed, then p's density at the new state
    void advance(PressureModel& p, double dt);
};

} // namespace spindrift::test
