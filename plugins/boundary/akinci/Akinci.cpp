// akinci — wall particles of Akinci et al. (2012), docs/MODELS.md §akinci: each wall particle b
// has a mass M_b in the fluid's pair sums and mirrors the pressure of the fluid particle it faces
// (p_b = p_i, ρ_b = ρ_i), giving the wall term M_b 2 p_i/ρ_i² ∇_i W_ib of the symmetric pressure
// gradient.
//
//   volume adaptive  M_b = ρ0 V_b, V_b = 1/Σ_k W_bk over the wall particles of every wall (self
//                    included): Akinci's volume, so an irregular or sparse wall of one layer
//                    contributes like fluid of rest density.
//   volume lattice   M_b = m, the fluid particle's mass (V_b = Δx^d): walls sampled on the fluid
//                    lattice with several layers then give exactly ρ0 next to a wall at rest.
//   volume auto      (default) per wall system: lattice when the wall is at least a kernel
//                    support thick (one of its particles has a full neighbourhood of wall
//                    particles, Σ_k W_bk ≥ 0.95 of the lattice's) and not a sheet (a surface
//                    sampled in one layer, BoundaryModel::ownNeighbourhood: a Poisson-disk layer
//                    in 3D sums above the lattice's by its density alone), else adaptive.
// The adaptive volume is meant for thin walls: on several lattice layers the surface layer's
// neighbourhood is half empty, so its V_b is about twice Δx^d and the first fluid row starts
// ~7–9 % above ρ0 (a 47 kPa corner particle in the dam-break tutorial at t = 0, which sprayed the
// column off the walls; the incompressible solvers pushed it off the walls in their first step);
// `auto` keeps Akinci's volume where it is right and the lattice volume where the wall is thick.
// (A mirrored pressure is the fluid particle's own, lower than a wall's below it: on a lattice
// wall a hydrostatic column settles a few percent denser near the floor than ρ0 g (H − z) says;
// the adami boundary extrapolates the wall's pressure instead.)
//
//   boundary { type akinci; volume auto; }   // auto (default) | adaptive | lattice
// and, as every boundary model, the collision of fluid particles with the walls (WallCollision.hpp):
//   boundary { type akinci; collision { distance 0; restitution 0.5; friction 0.1; } }
#include "BoundaryModel.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace {
using namespace spindrift;

class Akinci final : public BoundaryModel {
public:
    explicit Akinci(const ModelContext& c)
        : volume_(c.dict.getWordOrDefault("volume", {"auto", "adaptive", "lattice"}, "auto")) {
        collision_.read(c.dict);
    }

    void initialise(Scene& s) override {
        collision_.initialise(s);
        const Scalar rho0 = s.constants.rho0, m = s.constants.particleMass;
        const Scalar latticeSum = rho0 / m; // Σ W over a full lattice neighbourhood (latticeParticleMass)
        const auto boundaries = s.boundaries();
        for (ParticleSystem* wall : boundaries) {
            ParticleSystem& w = *wall;
            const std::vector<Scalar> sum = boundaryKernelSums(s, w);
            const Scalar fullest = w.size() ? *std::max_element(sum.begin(), sum.end()) : Scalar(0);
            const bool sheet = volume_ != "lattice" && ownNeighbourhood(s, w).sheet;
            const bool lattice = volume_ == "lattice" || (volume_ == "auto" && fullest >= Scalar(0.95) * latticeSum && !sheet);
            // a single layer (a Poisson-disk sampled mesh): Akinci's volume scaled so that the
            // first fluid row, Δx from it, sums ρ0 (below)
            const Scalar kappa = !lattice && sheet ? sheetFactor(s.kernel, s.physics.dimension, s.physics.particleSpacing) : Scalar(1);
            auto& mass = w.particles.addScalar("wallMass", {true, false});
            for (std::size_t b = 0; b < mass.size(); ++b) mass[b] = lattice ? m : kappa * rho0 / sum[b];
            w.mass = &mass;
            w.pressureMirrored = true;
            w.viscousVelocity = nullptr;
            std::ostringstream msg;
            msg << "akinci: wall '" << w.name() << "': " << (lattice ? "lattice" : "adaptive") << " volume"
                << (volume_ == "auto" ? " (volume auto: " : " (") << "fullest wall neighbourhood "
                << fullest / latticeSum << " of the lattice's)";
            if (kappa != 1) msg << ", a single layer: kappa " << kappa;
            log::info(msg.str());
        }
    }

private:
    // κ of a single layer's volume: Akinci's V_b = 1/Σ_k W_bk tends to 1/∫_plane W dA on a dense
    // flat layer, so a particle at height y over it sums ρ0 ∫_plane(y) W dA / ∫_plane(0) W dA from
    // it (0.47 ρ0 at y = Δx for the Wendland C2 at 3Δx in 3D) on top of the fluid's half of its
    // neighbourhood (0.75 ρ0 for the first row): 1.22 ρ0, a start that throws the summation
    // density solvers off the wall. κ makes the first fluid row, Δx over the layer, sum ρ0:
    //   κ = (1 − Σ_{lattice, y ≥ 0} W / Σ_lattice W) / [∫_plane(Δx) W dA / ∫_plane(0) W dA]
    static Scalar sheetFactor(const KernelTable& kt, int dim, Scalar dx) {
        const double R = kt.supportRadius();
        const auto W = [&](double x, double y, double z) {
            const double r = std::sqrt(x * x + y * y + z * z);
            return r < R ? double(kt.W(Scalar(r))) : 0.0;
        };
        const int n = int(std::ceil(R / dx)), nz = dim == 3 ? n : 0;
        double all = 0, above = 0;
        for (int k = -n; k <= n; ++k)
            for (int j = -n; j <= n; ++j)
                for (int l = -nz; l <= nz; ++l) {
                    const double w = W(j * dx, k * dx, l * dx);
                    all += w;
                    if (k >= 0) above += w;
                }
        const double atDx = planeSum(R, dim, dx, [&](double x, double z) { return W(x, dx, z); });
        const double atZero = planeSum(R, dim, dx, [&](double x, double z) { return W(x, 0, z); });
        return Scalar((1 - above / all) * atZero / atDx);
    }

    std::string volume_;
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, Akinci)
