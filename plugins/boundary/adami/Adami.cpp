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
// Contact (direct forcing on velocities, Becker, Tessendorf & Teschner 2009, IEEE TVCG 15(3)
// 493–503, doi:10.1109/TVCG.2008.107; Ihmsen, Akinci, Gissler & Teschner 2010 use it for PCISPH's
// walls, VRIPHYS 2010, doi:10.2312/PE/vriphys/vriphys10/079-088): a particle whose position at the
// end of the step would be nearer a boundary's face than contactDistance Δx (0.5 at rest; 0, the
// default, switches it off) loses the velocity with which it approaches the boundary there (correctAcceleration; its
// reaction on each boundary is reported as ForceKind::other). The wall pressure repels a particle
// only through its density: a lone particle, or the tip of a thin sheet, has so few fluid
// neighbours that it reached ρ0 only inside the wall. In the Colagrossi dam break the leading
// particle of the surge slid along the floor 0.3-0.7Δx below its face, at ρ = ρ0 and p = 0, and
// ran up the far wall 0.95Δx inside it (pcisph; every incompressible solver 0.95-1.13Δx, wcsph
// 0.71Δx late in the run, issue 35). Off by default: at 0.25 it stops the corner particles of
// a still column, whose share of wall density is a face's, from settling; iisph's bottom row read
// 2.4 % above hydrostatic (IisphTest's column) and relaxedPbf's column ended above η.
//
//   boundary { type adami; slip no; clampNegativePressure yes; contactDistance 0; }
#include "BoundaryModel.hpp"
#include "Log.hpp"
#include "PairLoop.hpp"
#include "Plugin.hpp"

#include <cmath>
#include <sstream>

namespace {
using namespace spindrift;

// M_b ∇W_ib of a boundary pair with the boundary particle where its own velocity takes it over
// the step (the fluid particle at its position at the end of the step), and W_ib there.
struct ContactKernel {
    Vec3 gradient;
    Scalar W;
};
inline ContactKernel contactKernel(const KernelTable& kt, const WallPair& q, Scalar dt) {
    const Scalar M = q.mass();
    if (!q.src.moving) return {M * q.gradW, M * q.W};
    const Vec3 r = q.r - dt * q.src.v[q.j];
    const KernelTable::Values k = kt.valuesSq(r.squaredNorm());
    return {(M * k.gradFactor) * r, M * k.W};
}

// The boundaries as a fluid particle at its position at the end of the step sees them: their
// share of its density, Σ_b M_b W_ib (a smooth function of the distance to a boundary's face:
// ρ0/2 at the face of a flat wall), Σ_b M_b ∇W_ib, whose direction is the boundaries' normal
// (smooth along a flat wall: a particle sliding along the wall's particles is not braked by their
// bumps), and their mass-weighted velocity.
struct ContactTerm {
    struct Sum {
        Scalar density = 0;
        Vec3 gradient = Vec3::Zero(), momentum = Vec3::Zero();
    };
    static constexpr bool visitsFluid = false;
    static constexpr bool usesGradient = true, usesKernel = true;
    struct Particle {};
    const KernelTable* kernel;
    Scalar dt;
    Particle particle(std::size_t) const { return {}; }
    void wall(const Particle&, const WallPair& q, Sum& sum) const {
        const ContactKernel k = contactKernel(*kernel, q, dt);
        sum.density += k.W;
        sum.gradient += k.gradient;
        if (q.src.moving) sum.momentum += k.W * q.src.v[q.j];
    }
};

// The pairs of the contact's reactions (addReactions reads only its kernel needs).
struct ContactReactionTerm {
    static constexpr bool usesGradient = true, usesKernel = true;
    using Particle = std::size_t;
    Particle particle(std::size_t i) const { return i; }
};

class Adami final : public BoundaryModel {
public:
    explicit Adami(const ModelContext& c)
        : slip_(c.dict.getOrDefault<bool>("slip", false)),
          clampNegative_(c.dict.getOrDefault<bool>("clampNegativePressure", true)),
          contact_(c.dict.getOrDefault<double>("contactDistance", 0.0)) {
        if (!(contact_ >= 0 && contact_ <= 0.5))
            throw InputError(c.dict.locationOf("contactDistance"),
                             "contactDistance (from a wall's face, in particle spacings; 0.5 at rest) must be in [0, 0.5]",
                             "contactDistance");
    }

    void initialise(Scene& s) override {
        const Scalar m = s.constants.particleMass, latticeSum = s.constants.rho0 / m;
        const auto& kt = s.kernel;
        contactDensity_ = contact_ > 0 ? flatWallShare(s, Scalar(contact_)) : Scalar(0);
        for (ParticleSystem* wall : s.boundaries()) {
            ParticleSystem& w = *wall;
            auto& mass = w.particles.addScalar("wallMass", {true, false});
            std::fill(mass.begin(), mass.end(), m);
            w.mass = &mass;
            w.pressureMirrored = false;
            w.particles.addScalar("pressure", {true, false}); // the wall's own, written
            w.particles.addScalar("density", {true, false});
            w.viscousVelocity = &w.particles.addVector("viscousVelocity", {false, false});
            // the walls must cover the support: some particle has a full wall neighbourhood
            const NeighbourList list = s.search.listBetween(w.index, w.index);
            const auto& x = w.particles.position();
            Scalar fullest = 0;
            for (std::size_t b = 0; b < x.size(); ++b) {
                Scalar sum = kt.W0();
                forEachNeighbour(list, x, x, b, [&](Index, const Vec3&, Scalar r2) { sum += kt.WSq(r2); });
                fullest = std::max(fullest, sum / latticeSum);
            }
            if (fullest < Scalar(0.95)) {
                std::ostringstream msg;
                msg << "adami: wall '" << w.name() << "' is thinner than the kernel support (its fullest wall "
                    << "neighbourhood is " << fullest << " of a full one): give it more layers, or the fluid "
                    << "sees a truncated wall and may leak through corners";
                log::warning(msg.str());
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

    // Contact (direct forcing, Becker, Tessendorf & Teschner 2009, on velocities): a fluid particle
    // whose position at the end of the step, x + Δt (v + Δt a) (symplectic Euler), would be
    // nearer a boundary's face than contactDistance Δx loses the part of its velocity v + Δt a
    // that approaches the boundary along its normal n = −Σ_b M_b ∇W_ib/|…|, relative to the
    // boundary's own velocity: Δa_i = −min(0, v_rel·n) n/Δt. It stops where it is and keeps its
    // slide along the wall; nothing is pushed. "Nearer the face" is read from the boundaries'
    // share of its density: at least ρ_c, their share at contactDistance from the face of a flat
    // wall of the case's lattice (initialise). At rest a particle is 0.5Δx from the face; in a 90°
    // corner its share is higher (0.53 ρ0 for the Wendland C2 at 4Δx in 2D), so it counts as
    // touching, which changes nothing while it does not move into the corner.
    void correctAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) override {
        const Scalar dt = step.dt;
        const std::size_t n = fluid.size();
        contacts_ = 0;
        if (!(contactDensity_ > 0) || !(dt > 0) || s.boundaries().empty()) return;
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        auto& a = fluid.particles.acceleration();
        predicted_.resize(n);
        change_.assign(n, Vec3::Zero());
        share_.resize(n);
        forEachIndex(n, [&](std::size_t i) { predicted_[i] = x[i] + dt * (v[i] + dt * a[i]); });
        const Scalar limit = contactDensity_, invDt = 1 / dt;
        forEachPairSum(s, fluid, predicted_, ContactTerm{&s.kernel, dt}, [&](std::size_t i, const auto&, const ContactTerm::Sum& c) {
            const Scalar length2 = c.gradient.squaredNorm();
            if (c.density < limit || !(length2 > 0)) return;
            const Vec3 normal = -c.gradient / std::sqrt(length2);
            const Vec3 relative = v[i] + dt * a[i] - c.momentum / c.density;
            const Scalar approach = relative.dot(normal);
            if (approach < 0) {
                change_[i] = -(approach * invDt) * normal;
                a[i] += change_[i];
                share_[i] = c.gradient / length2; // M_b ∇W_ib · this: boundary particle b's share (Σ = 1)
            }
        });
        contacts_ = parallelAny(n, [&](std::size_t i) { return change_[i] != Vec3::Zero(); }) ? 1 : 0;
    }

    // The contact's Δa_i acts on the boundary particles b of i's normal in their shares
    // M_b ∇W_ib·Σ_b M_b ∇W_ib/|Σ_b M_b ∇W_ib|² (summing to one): a_ib = share_b Δa_i, so the
    // boundaries take −m Δa_i in all, the change of the fluid's momentum.
    void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const override {
        if (!contacts_) return;
        const Scalar dt = step.dt;
        spindrift::addReactions(s, fluid, predicted_, ContactReactionTerm{}, [&](std::size_t i, std::size_t, const WallPair& q) {
            if (change_[i] == Vec3::Zero()) return Vec3(Vec3::Zero());
            return Vec3(contactKernel(s.kernel, q, dt).gradient.dot(share_[i]) * change_[i]);
        }, ForceKind::other, r);
    }

private:
    // The boundaries' share of the density of a particle 'distance' Δx from the face of a flat wall
    // of particles of mass m on the case's lattice (layers covering the support): Σ_b m W_ib.
    static Scalar flatWallShare(const Scene& s, Scalar distance) {
        const double dx = s.physics.particleSpacing, h = s.constants.supportRadius;
        const int reach = int(std::ceil(h / dx)) + 1, dim = s.physics.dimension;
        double sum = 0;
        for (int k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k)
            for (int j = 0; j <= reach; ++j)
                for (int i = -reach; i <= reach; ++i) {
                    const Vec3 r(Scalar(i * dx), Scalar((distance + 0.5 + j) * dx), Scalar(k * dx));
                    sum += double(s.kernel.W(r.norm()));
                }
        return Scalar(sum * s.constants.particleMass);
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
    double contact_;            // contactDistance: Δx from a boundary's face (0: no contact)
    Scalar contactDensity_ = 0; // the boundaries' share of the density there
    // the last correction: the predicted positions, each particle's Δa and its shares' vector,
    // whether any particle was touched
    std::vector<Vec3> predicted_, change_, share_;
    int contacts_ = 0;
};
} // namespace

SPINDRIFT_PLUGIN(BoundaryModel, Adami)
