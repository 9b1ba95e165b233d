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
            const bool lattice = volume_ == "lattice" ||
                                 (volume_ == "auto" && fullest >= Scalar(0.95) * latticeSum && !ownNeighbourhood(s, w).sheet);
            auto& mass = w.particles.addScalar("wallMass", {true, false});
            for (std::size_t b = 0; b < mass.size(); ++b) mass[b] = lattice ? m : rho0 / sum[b];
            w.mass = &mass;
            w.pressureMirrored = true;
            w.viscousVelocity = nullptr;
            std::ostringstream msg;
            msg << "akinci: wall '" << w.name() << "': " << (lattice ? "lattice" : "adaptive") << " volume"
                << (volume_ == "auto" ? " (volume auto: " : " (") << "fullest wall neighbourhood "
                << fullest / latticeSum << " of the lattice's)";
            log::info(msg.str());
        }
    }

private:
    std::string volume_;
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, Akinci)
