// Spindrift — the collision of fluid particles with the boundaries (walls and bodies), written once
// for every boundary model (BoundaryModel's collision_): a fluid particle whose position at the end of
// the step, x* = x + Δt (v + Δt a) (symplectic Euler's), would be nearer a boundary's face than
// `distance` Δx (0: would cross the face) and moves towards it, relative to the boundary's own
// velocity v_w, has that velocity u = v + Δt a − v_w changed as by a collision with restitution e
// and Coulomb friction μ:
//   u_n = u·n < 0:   Δu = −(1 + e) u_n n − min(1, μ (1 + e) |u_n| / |u_t|) u_t,   u_t = u − u_n n,
//   a_i += Δu/Δt
// (e = 0, μ = 0: the approach is stopped and the slide kept: direct forcing, Becker, Tessendorf &
// Teschner 2009, IEEE TVCG 15(3) 493–503, doi:10.1109/TVCG.2008.107). The response with energy
// loss is seed 000's (Perea & Cordero §8, after Solenthaler et al. 2011, VRIPHYS'11 39–46; the
// impulse form above is the standard one, the seed's text gives no formula). "Nearer the face"
// is read from the boundaries' share of the particle's density at x*, Σ_b M_b W(x* − x*_b)
// (x*_b where the boundary's velocity takes it): at least ρ_c, the share of a flat lattice wall
// at `distance` from its face; n = −Σ_b M_b ∇W / |…| points from the boundary into the fluid;
// v_w = Σ_b M_b W v_b / Σ_b M_b W. A particle at rest sits 0.5Δx from the face, so `distance`
// is in [0, 0.5]. The boundaries take −m Δu/Δt in all (ForceKind::other), shared over the
// boundary particles of i's normal in proportion to M_b ∇W_ib · Σ_b M_b ∇W_ib / |Σ_b M_b ∇W_ib|².
//
// On by default with distance 0, e = 0, μ = 0: no particle centre is carried past a face (issue 35:
// the incompressible solvers' surge ran 0.5-1.1Δx into the Colagrossi tank's walls, wcsph's 0.8Δx;
// with it 0.01-0.04Δx); `collision no;` switches it off.
//   boundary { type adami; collision { distance 0; restitution 0; friction 0; } }
//   (adami's `contactDistance d;` is the same as `collision { distance d; }`)
#pragma once

#include "Dictionary.hpp"
#include "PairLoop.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace spindrift {

class WallCollision {
public:
    // From a boundary model's dictionary: its `collision { }` sub-dictionary (the defaults when
    // there is none), or `collision no;` (off).
    void read(const Dictionary& boundary) {
        if (boundary.found("collision") && !boundary.isDict("collision")) {
            enabled_ = boundary.get<bool>("collision");
            return;
        }
        enabled_ = true;
        const Dictionary* c = boundary.findDict("collision");
        if (!c) return;
        distance_ = c->getOrDefault<double>("distance", 0.0);
        restitution_ = c->getOrDefault<double>("restitution", 0.0);
        friction_ = c->getOrDefault<double>("friction", 0.0);
        if (!(distance_ >= 0 && distance_ <= 0.5))
            throw InputError(c->locationOf("distance"),
                             "distance (from a wall's face, in particle spacings; 0.5 at rest) must be in [0, 0.5]", "distance");
        if (!(restitution_ >= 0 && restitution_ <= 1))
            throw InputError(c->locationOf("restitution"), "restitution must be in [0, 1]", "restitution");
        if (!(friction_ >= 0))
            throw InputError(c->locationOf("friction"), "friction must not be negative", "friction");
        c->checkAllKeywordsUsed();
    }
    // A contact at 'distance' Δx that stops the approach (e = 0, μ = 0): adami's contactDistance.
    void enableContact(double distance) {
        enabled_ = true;
        distance_ = distance;
    }
    bool enabled() const { return enabled_; }

    void initialise(const Scene& s) { limit_ = enabled_ ? flatWallShare(s, Scalar(distance_)) : Scalar(0); }

    // a_i of the particles of 'fluid' that would reach a boundary (after the pressure model).
    void apply(const Scene& s, ParticleSystem& fluid, Scalar dt) {
        const std::size_t n = fluid.size();
        touched_ = false;
        if (!enabled_ || !(dt > 0) || s.boundaries().empty()) return;
        const auto& x = fluid.particles.position();
        const auto& v = fluid.particles.velocity();
        auto& a = fluid.particles.acceleration();
        predicted_.resize(n);
        change_.assign(n, Vec3::Zero());
        share_.resize(n);
        forEachIndex(n, [&](std::size_t i) { predicted_[i] = x[i] + dt * (v[i] + dt * a[i]); });
        const Scalar limit = limit_, invDt = 1 / dt, e = Scalar(restitution_), mu = Scalar(friction_);
        forEachPairSum(s, fluid, predicted_, Term{&s.kernel, dt}, [&](std::size_t i, const auto&, const Term::Sum& c) {
            const Scalar length2 = c.gradient.squaredNorm();
            if (c.density < limit || !(length2 > 0)) return;
            const Vec3 normal = -c.gradient / std::sqrt(length2);
            const Vec3 relative = v[i] + dt * a[i] - c.momentum / c.density;
            const Scalar approach = relative.dot(normal);
            if (!(approach < 0)) return;
            Vec3 du = -((1 + e) * approach) * normal;
            const Vec3 slide = relative - approach * normal;
            const Scalar slideSpeed = slide.norm();
            if (mu > 0 && slideSpeed > 0) du -= std::min(Scalar(1), mu * (1 + e) * -approach / slideSpeed) * slide;
            change_[i] = invDt * du;
            a[i] += change_[i];
            share_[i] = c.gradient / length2; // M_b ∇W_ib · this: boundary particle b's share (Σ = 1)
        });
        touched_ = parallelAny(n, [&](std::size_t i) { return change_[i] != Vec3::Zero(); });
    }

    // The reactions of the last apply() on the boundaries (above).
    void addReactions(const Scene& s, const ParticleSystem& fluid, Scalar dt, Reactions& r) const {
        if (!touched_) return;
        spindrift::addReactions(s, fluid, predicted_, ReactionTerm{}, [&](std::size_t i, std::size_t, const WallPair& q) {
            if (change_[i] == Vec3::Zero()) return Vec3(Vec3::Zero());
            return Vec3(kernelAtEnd(s.kernel, q, dt).gradient.dot(share_[i]) * change_[i]);
        }, ForceKind::other, r);
    }

    // Σ_b m W_ib of a particle 'distance' Δx from the face of a flat wall of particles of the
    // fluid's mass m on the case's lattice, its layers covering the support (diffuseParticles reads
    // it too: past a face, a diffuse particle is in the wall).
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

private:
    // M_b ∇W_ib and M_b W_ib with boundary particle b where its own velocity takes it over the step.
    struct KernelAtEnd {
        Vec3 gradient;
        Scalar W;
    };
    static KernelAtEnd kernelAtEnd(const KernelTable& kt, const WallPair& q, Scalar dt) {
        const Scalar M = q.mass();
        if (!q.src.moving) return {M * q.gradW, M * q.W};
        const Vec3 r = q.r - dt * q.src.v[q.j];
        const KernelTable::Values k = kt.valuesSq(r.squaredNorm());
        return {(M * k.gradFactor) * r, M * k.W};
    }

    // The boundaries as a fluid particle at its position at the end of the step sees them: their
    // share of its density (a smooth function of the distance to a face: about ρ0/2 at the face of
    // a flat wall), Σ_b M_b ∇W_ib (smooth along a flat wall: a particle sliding along it is not
    // braked by the bumps of its particles) and their mass-weighted velocity.
    struct Term {
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
            const KernelAtEnd k = kernelAtEnd(*kernel, q, dt);
            sum.density += k.W;
            sum.gradient += k.gradient;
            if (q.src.moving) sum.momentum += k.W * q.src.v[q.j];
        }
    };
    // The pairs of the reactions (addReactions reads only its kernel needs).
    struct ReactionTerm {
        static constexpr bool usesGradient = true, usesKernel = true;
        using Particle = std::size_t;
        Particle particle(std::size_t i) const { return i; }
    };

    bool enabled_ = false;
    double distance_ = 0, restitution_ = 0, friction_ = 0;
    Scalar limit_ = 0; // ρ_c
    // the last apply(): the predicted positions, each particle's Δa and its shares' vector
    std::vector<Vec3> predicted_, change_, share_;
    bool touched_ = false;
};

} // namespace spindrift
