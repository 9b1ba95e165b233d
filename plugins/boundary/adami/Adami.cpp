// adami — the generalised wall boundary condition of Adami, Hu & Adams (2012), J. Comput. Phys.
// 231(21), 7057–7075, doi:10.1016/j.jcp.2012.05.005; docs/MODELS.md §adami.
//
// Several layers of dummy particles on the fluid lattice (layers·Δx at least the support h) act
// in every pair sum as fluid particles of mass M_b = m (the hydrodynamic mass) with a pressure,
// density and velocity of their own, extrapolated from the fluid around each wall particle w:
//   p_w = [Σ_f p_f W_wf + (g − a_w)·Σ_f ρ_f r_wf W_wf] / Σ_f W_wf,   r_wf = x_w − x_f   (eq. 27)
//   ρ_w = ρ(p_w), the pressure model's equation of state inverted (ρ0 for incompressible solvers)
//   v̂_w = 2 v_w − Σ_f v_f W_wf / Σ_f W_wf                                    (eqs. 22–23)
// a_w and v_w are the wall's own acceleration and velocity (zero when fixed); v̂_w is the
// velocity the viscous terms see (no slip: the fluid's velocity mirrored through the wall's);
// the continuity equation and the pressure term use the wall's own. With `slip yes` the viscous
// terms see the fluid's own average velocity at the wall instead (free slip: no shear). A wall
// particle without fluid in its support keeps p_w = 0, ρ_w = ρ0, v̂_w = v_w. Pressure solvers
// that change the fluid's pressure within a step carry it to the walls (updatePressure).
// clampNegativePressure (yes): p_w ≥ 0, so a wall does not pull a free-surface flow onto it
// where the hydrostatic term turns negative (a wall above the fluid).
// Collision with the walls (WallCollision.hpp, `collision { }`, on by default at the face): the
// wall pressure repels a particle only through its density, and a lone particle, or the tip of a
// thin sheet, has so few fluid neighbours that it reached ρ0 only inside the wall (the Colagrossi
// dam break's surge 0.3-0.7Δx below the floor's face, every incompressible solver 0.5-1.1Δx inside
// the far wall, issue 35). `contactDistance d` (0 < d ≤ 0.5) is `collision { distance d; }`,
// the approach stopped d Δx from a face: at 0.25 it stopped the corner particles of a still
// column, whose share of wall density is above a flat face's, from settling (iisph's bottom row
// 2.4 % above hydrostatic); at the face (the default) the still tank is unchanged bit for bit.
// Thin walls (`volume`): a wall of one layer (a mesh's Poisson-disk sampling) standing for the
// lattice's several cannot take the fluid's mass m a particle: sampled at 0.5–0.65 Δx, that
// pushed the water's bottom row 20 % harder per unit pressure than a lattice wall (a still tank's
// bottom row 20 % below hydrostatic). There M_b = κ ρ0 / Σ_k W_bk, Akinci et al.'s (2012)
// adaptive volume (independent of how densely the layer is sampled), scaled by κ so that a flat
// layer gives a fluid particle Δx from it (where the water rests against it) the normal kernel
// gradient Σ_b V_b ∂W/∂n of the lattice wall it stands for (κ from the kernel, once).
//   volume auto      (default) per wall: adaptive where the wall is a sheet (most of its
//                    particles' neighbourhoods flat: BoundaryModel::ownNeighbourhood), else
//                    lattice (M_b = m: lattice walls run as they always did)
//   volume lattice | adaptive
//
//   boundary { type adami; slip no; clampNegativePressure yes; contactDistance 0; volume auto; }
//   boundary { type adami; collision { distance 0; restitution 0.5; friction 0.1; } }
#include "BoundaryModel.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace {
using namespace spindrift;

class Adami final : public BoundaryModel {
public:
    explicit Adami(const ModelContext& c)
        : slip_(c.dict.getOrDefault<bool>("slip", false)),
          clampNegative_(c.dict.getOrDefault<bool>("clampNegativePressure", true)),
          volume_(c.dict.getWordOrDefault("volume", {"auto", "lattice", "adaptive"}, "auto")) {
        collision_.read(c.dict);
        const double contact = c.dict.getOrDefault<double>("contactDistance", 0.0);
        if (!(contact >= 0 && contact <= 0.5))
            throw InputError(c.dict.locationOf("contactDistance"),
                             "contactDistance (from a wall's face, in particle spacings; 0.5 at rest) must be in [0, 0.5]",
                             "contactDistance");
        if (contact > 0 && c.dict.found("collision"))
            throw InputError(c.dict.locationOf("contactDistance"),
                             "contactDistance and collision { } say the same thing: give the distance in collision { distance ...; }",
                             "contactDistance");
        if (contact > 0) collision_.enableContact(contact);
    }

    void initialise(Scene& s) override {
        const Scalar m = s.constants.particleMass, latticeSum = s.constants.rho0 / m;
        const auto& kt = s.kernel;
        collision_.initialise(s);
        for (ParticleSystem* wall : s.boundaries()) {
            ParticleSystem& w = *wall;
            w.pressureMirrored = false;
            w.particles.addScalar("pressure", {true, false}); // the wall's own, written
            w.particles.addScalar("density", {true, false});
            w.viscousVelocity = &w.particles.addVector("viscousVelocity", {false, false});
            const Neighbourhood own = ownNeighbourhood(s, w);
            const Scalar fullest = own.fullest / latticeSum;
            const bool lattice = volume_ == "lattice" || (volume_ == "auto" && !own.sheet);
            auto& mass = w.particles.addScalar("wallMass", {true, false});
            Scalar kappa = 1;
            if (lattice) {
                std::fill(mass.begin(), mass.end(), m);
            } else {
                kappa = thinWallFactor(kt, s.physics.dimension, s.physics.particleSpacing);
                const std::vector<Scalar> sum = boundaryKernelSums(s, w);
                for (std::size_t b = 0; b < mass.size(); ++b) mass[b] = kappa * s.constants.rho0 / sum[b];
            }
            w.mass = &mass;
            std::ostringstream msg;
            if (lattice && fullest < Scalar(0.95)) {
                msg << "adami: wall '" << w.name() << "' is thinner than the kernel support (its fullest wall "
                    << "neighbourhood is " << fullest << " of a full one) with lattice volumes: give it more "
                    << "layers or `volume adaptive`, or the fluid sees a truncated wall and may leak through corners";
                log::warning(msg.str());
            } else if (!lattice) {
                msg << "adami: wall '" << w.name() << "': adaptive volume, kappa " << kappa << " (fullest wall "
                    << "neighbourhood " << fullest << " of the lattice's)";
                log::info(msg.str());
            }
        }
    }

    // (every boundary from every fluid; with one fluid that is its pressure)
    void update(Scene& s, const Step&) override {
        for (const ParticleSystem* fluid : s.ofRole(SystemRole::fluid))
            extrapolate(s, *fluid, fluid->particles.pressure(), true);
    }
    void updatePressure(Scene& s, const ParticleSystem& fluid, const std::vector<Scalar>& fluidPressure) override {
        extrapolate(s, fluid, fluidPressure, false);
    }

private:
    // κ of the adaptive volume: the normal kernel gradient a lattice wall (layers at Δx, 2Δx, ...
    // below a particle, every lattice column) gives, over that of a continuous layer Δx below it
    // whose volume per unit area is 1/∫W over the layer's plane (the adaptive volume's limit):
    //   κ = Σ_lattice Δx^d (−∂W/∂y) / [∫_plane(Δx) (−∂W/∂y) dA / ∫_plane(0) W dA]
    static Scalar thinWallFactor(const KernelTable& kt, int dim, Scalar dx) {
        const double R = kt.supportRadius();
        const auto minusDWdy = [&](double x, double y, double z) {
            const double r = std::sqrt(x * x + y * y + z * z);
            return r > 0 && r < R ? -double(kt.dWdr(Scalar(r))) * y / r : 0.0;
        };
        const int n = int(std::ceil(R / dx));
        const int nz = dim == 3 ? n : 0;
        double lattice = 0;
        for (int k = 1; k <= n; ++k)
            for (int j = -n; j <= n; ++j)
                for (int l = -nz; l <= nz; ++l) lattice += minusDWdy(j * dx, k * dx, l * dx);
        lattice *= std::pow(double(dx), dim);
        const double gradient = planeSum(R, dim, dx, [&](double x, double z) { return minusDWdy(x, dx, z); });
        const double weight = planeSum(R, dim, dx, [&](double x, double z) {
            const double r = std::sqrt(x * x + z * z);
            return r < R ? double(kt.W(Scalar(r))) : 0.0;
        });
        return Scalar(lattice * weight / gradient); // (the plane's element cancels)
    }

    // p_w, ρ_w (and v̂_w when 'velocities') of every boundary from the pressure p of a fluid.
    void extrapolate(Scene& s, const ParticleSystem& fluid, const std::vector<Scalar>& p, bool velocities) const {
        const auto& kt = s.kernel;
        const auto& xf = fluid.particles.position();
        const auto& vf = fluid.particles.velocity();
        const auto& rhof = fluid.particles.density();
        const Vec3 g = s.physics.gravity;
        const SceneConstants& c = s.constants;
        const bool clamp = clampNegative_, slip = slip_;
        for (ParticleSystem* wall : s.boundaries()) {
            ParticleSystem& w = *wall;
            const NeighbourList& list = s.search.reverseNeighbours(fluid.index, w.index);
            const auto& xw = w.particles.position();
            const auto& vw = w.particles.velocity();
            const auto& aw = w.particles.acceleration();
            auto& pw = w.particles.pressure();
            auto& rhow = w.particles.density();
            auto& vv = *w.particles.findVector("viscousVelocity");
            forEachIndex(xw.size(), [&](std::size_t b) {
                Scalar sumW = 0, sumP = 0;
                Vec3 sumRhoR = Vec3::Zero(), sumV = Vec3::Zero();
                forEachNeighbour(list, xw, xf, b, [&](Index f, const Vec3& r, Scalar r2) {
                    const Scalar W = kt.WSq(r2);
                    sumW += W;
                    sumP += p[f] * W;
                    sumRhoR += (rhof[f] * W) * r;
                    if (velocities) sumV += W * vf[f];
                });
                if (!(sumW > 0)) {
                    pw[b] = 0;
                    rhow[b] = c.rho0;
                    if (velocities) vv[b] = vw[b];
                    return;
                }
                Scalar pb = (sumP + (g - aw[b]).dot(sumRhoR)) / sumW;
                if (clamp) pb = std::max(pb, Scalar(0));
                pw[b] = pb;
                rhow[b] = c.densityAt(pb);
                if (velocities) {
                    const Vec3 fluidVelocity = sumV / sumW;
                    vv[b] = slip ? fluidVelocity : Vec3(2 * vw[b] - fluidVelocity);
                }
            });
        }
    }

    bool slip_, clampNegative_;
    std::string volume_;
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, Adami)
