// Spindrift — the collision of fluid particles with the boundaries (walls and bodies), written once
// for every boundary model (BoundaryModel's collision_): a fluid particle whose position at the end of
// the step, x* = x + Δt (v + Δt a + δv) (symplectic Euler's; δv a shifting model's, computed before
// it), would be nearer a boundary's face than
// `distance` Δx (0: would cross the face) and moves towards it, relative to the boundary's own
// velocity v_w, has that velocity u = v + Δt a + δv − v_w changed as by a collision with restitution e
// and Coulomb friction μ:
//   u_n = u·n < 0:   Δu = −(1 + e) u_n n − min(1, μ (1 + e) |u_n| / |u_t|) u_t,   u_t = u − u_n n,
//   a_i += Δu/Δt
// and, when it approaches, at least the normal speed that ends the step no further past the face
// than x_i (a position-based bound: the share's normal is tilted by the wall particles' bumps near
// the face, docs/MODELS.md §collision)
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
// A single layer on a surface (a Poisson-disk mesh wall, whose particles carry the surface's
// normal) is read from the surface itself: its face lies a quarter spacing in front of the layer,
// crossed where x* passes it within a particle's footprint on the layer (Term, below).
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
#include <array>
#include <cmath>
#include <limits>
#include <utility>
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
        shareChange_.resize(n);
        share_.resize(n);
        const auto boundaries = s.boundaries();
        const bool sheets = std::any_of(boundaries.begin(), boundaries.end(),
                                        [](const ParticleSystem* b) { return b->surfaceNormal != nullptr; });
        if (sheets) hits_.assign(n, {});
        else hits_.clear();
        // the drift of the step: v + Δt a, and a shifting model's δv (computed before this)
        const std::vector<Vec3>* shift = fluid.particles.findVector("shiftingVelocity");
        const auto drift = [&](std::size_t i) { return shift ? Vec3((*shift)[i]) : Vec3(Vec3::Zero()); };
        forEachIndex(n, [&](std::size_t i) { predicted_[i] = x[i] + dt * (v[i] + dt * a[i] + drift(i)); });
        const Scalar limit = limit_, invDt = 1 / dt, e = Scalar(restitution_), mu = Scalar(friction_);
        const Scalar maxEstimate = Scalar(0.25) * s.physics.particleSpacing;
        const Term term{&s.kernel, dt, Scalar(sheetFace + distance_) * s.physics.particleSpacing, x.data(),
                        predicted_.data()};
        forEachPairSum(s, fluid, predicted_, term, [&](std::size_t i, const auto&, const Term::Sum& c) {
            // the faces the step would cross (or come nearer than 'distance'): the one the boundaries'
            // share tells, and those of the sheets hit (up to three, a corner's)
            const bool byShare = c.sheets == 0 && c.density >= limit && c.gradient.squaredNorm() > 0;
            if (!byShare && c.sheets == 0) return;
            const Vec3 shareNormal = byShare ? Vec3(-c.gradient.normalized()) : Vec3(Vec3::Zero());
            const Vec3 shareVelocity = byShare ? Vec3(c.momentum / c.density) : Vec3(Vec3::Zero());
            const Vec3 u0 = v[i] + dt * a[i] + drift(i);
            // how much further past the face than x_i the step would take x*, (share* − max(ρ_c,
            // share now))/|∇share| (to 1 % within 0.25 Δx of a flat wall; capped there), and the
            // normal speed that ends the step no further past it
            const Scalar past = byShare ? std::min((c.density - std::max(limit, c.densityNow)) / c.gradient.norm(), maxEstimate)
                                        : Scalar(0);
            const Scalar shareLeave = byShare ? (u0 - shareVelocity).dot(shareNormal) + past * invDt : Scalar(0);
            Vec3 u = u0, shareChange = Vec3::Zero();
            // each face's response in turn; a second sweep stops what the first left approaching
            // another face of a corner
            for (int sweep = 0; sweep < 2; ++sweep) {
                const Scalar es = sweep == 0 ? e : Scalar(0), mus = sweep == 0 ? mu : Scalar(0);
                if (byShare) shareChange += response(u, shareNormal, shareVelocity, es, mus, shareLeave);
                for (int k = 0; k < c.sheets; ++k)
                    hits_[i][std::size_t(k)].change += response(u, c.sheet[k].normal, c.sheet[k].velocity, es, mus);
            }
            if (u == u0) return;
            change_[i] = invDt * (u - u0);
            a[i] += change_[i];
            // who takes the reaction: of the share's face's part the boundary particles b in
            // proportion to M_b ∇W_ib · share_ (Σ = 1), of each sheet's the particle hit
            shareChange_[i] = invDt * shareChange;
            share_[i] = byShare ? Vec3(c.gradient / c.gradient.squaredNorm()) : Vec3(Vec3::Zero());
            for (int k = 0; k < c.sheets; ++k) {
                SheetHit& hit = hits_[i][std::size_t(k)];
                hit.system = c.sheet[k].system;
                hit.particle = c.sheet[k].particle;
                hit.change *= invDt;
            }
        });
        touched_ = parallelAny(n, [&](std::size_t i) { return change_[i] != Vec3::Zero(); });
    }

    // The reactions of the last apply() on the boundaries (above).
    void addReactions(const Scene& s, const ParticleSystem& fluid, Scalar dt, Reactions& r) const {
        if (!touched_) return;
        spindrift::addReactions(s, fluid, predicted_, ReactionTerm{}, [&](std::size_t i, std::size_t, const WallPair& q) {
            if (change_[i] == Vec3::Zero()) return Vec3(Vec3::Zero());
            Vec3 reaction = kernelAtEnd(s.kernel, q, dt).gradient.dot(share_[i]) * shareChange_[i];
            if (q.src.normal)
                for (const SheetHit& hit : hits_[i])
                    if (hit.system == q.src.system && hit.particle == q.j) reaction += hit.change;
            return reaction;
        }, ForceKind::other, r);
    }

    // Σ_b m W_ib of a particle 'distance' Δx from the face of a flat wall of particles of the
    // fluid's mass m on the case's lattice, its layers covering the support (diffuseParticles reads
    // it too: past a face, a diffuse particle is in the wall).
    // The least over the particle's place along the wall (the share ripples with it, by 6·10⁻⁴ of
    // itself on the Wendland C2 at 4Δx, 0.0008 Δx of height): a particle is stopped at the face or
    // just before it, never past.
    static Scalar flatWallShare(const Scene& s, Scalar distance) {
        const double dx = s.physics.particleSpacing, h = s.constants.supportRadius;
        const int reach = int(std::ceil(h / dx)) + 1, dim = s.physics.dimension, phases = 4;
        double least = std::numeric_limits<double>::max();
        for (int px = 0; px <= phases; ++px)
            for (int pz = 0; pz <= (dim == 3 ? phases : 0); ++pz) {
                const double ox = 0.5 * px / phases, oz = 0.5 * pz / phases; // a quarter of the cell, by symmetry
                double sum = 0;
                for (int k = (dim == 3 ? -reach : 0); k <= (dim == 3 ? reach : 0); ++k)
                    for (int j = 0; j <= reach; ++j)
                        for (int i = -reach; i <= reach; ++i) {
                            const Vec3 r(Scalar((i + ox) * dx), Scalar((distance + 0.5 + j) * dx),
                                         Scalar((k + oz) * dx)); // (oz is 0 in 2D)
                            sum += double(s.kernel.W(r.norm()));
                        }
                least = std::min(least, sum);
            }
        return Scalar(least * s.constants.particleMass);
    }

private:
    // The collision of velocity u with a face of normal n moving at w (above): u changed, the
    // change returned (zero when u does not approach it). 'leave' is the least normal speed
    // (relative to w) at which the step ends no further past the face than it starts: the share's
    // normal is tilted by the bumps of the wall's particles (a few degrees this near the face), so a
    // particle sliding along a floor at 1.5 m/s, its approach along that normal stopped every step,
    // still crept 0.02 Δx below it (Colagrossi's H/80). Only an approaching particle is held to it:
    // pushing receding ones too kicked the particles sliding at a wall's face, and a coarse standing
    // wave (validation/standingWave2D at dx 0.05, pcisph) lost 21.7 % a period instead of 12.6 %.
    static Vec3 response(Vec3& u, const Vec3& n, const Vec3& w, Scalar e, Scalar mu,
                         Scalar leave = std::numeric_limits<Scalar>::lowest()) {
        const Vec3 relative = u - w;
        const Scalar approach = relative.dot(n);
        const Scalar normal = approach < 0 ? std::max(-e * approach, leave) : approach;
        if (!(normal > approach)) return Vec3::Zero();
        Vec3 du = (normal - approach) * n;
        const Vec3 slide = relative - approach * n;
        const Scalar slideSpeed = slide.norm();
        if (mu > 0 && slideSpeed > 0) du -= std::min(Scalar(1), mu * (normal - approach) / slideSpeed) * slide;
        u += du;
        return du;
    }

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
    // A single layer on a surface (boundary particles with surface normals, ParticleSystem::
    // surfaceNormal) is a sheet: its share peaks on the layer and its gradient vanishes there
    // (and near a corner points along the other faces), so they tell neither the distance nor the
    // side. Each of its particles b stands instead for the piece of surface around it: its
    // tangent plane within a footprint of radius 2.1 r (r the Poisson-disk radius: every point of
    // the surface lies within 1.06 r of a sample, but near an edge that sample may be one of the
    // next face, whose own keep a face's up to r from the edge: twice that). The particle hits
    // the sheet where x* comes within a footprint nearer the layer's plane than its face,
    // 'sheetFace' in front of it, and 'distance', from the side x_i is on (water on either side of
    // a baffle stays on its side): the deepest such hit of each face (up to a corner's three)
    // gives its normal (n_b, turned to x_i's side), the surface's velocity and the particle that
    // takes the reaction. Where a sheet is hit, its faces alone: the share's normal is tilted
    // near a sheet, and the two together would hold a particle sliding down the face.
    static constexpr std::size_t noContact = std::size_t(-1);
    // [Δx] in front of the layer. The layer stands for the first layer of a lattice wall (its
    // adaptive volume is made so; the fill keeps the fluid a spacing from it), whose face lies half
    // a spacing in front; but its own pressure holds water at rest nearer (0.33 Δx in the corners
    // of a 2D tank, MeshTest), and the face only has to catch what the pressure lets through.
    static constexpr double sheetFace = 0.25;
    static constexpr int maxSheetContacts = 3; // a corner's faces
    struct SheetContact {
        Scalar depth = 0; // (x*_i − x*_b)·n_b − (face + distance), < 0
        Vec3 normal = Vec3::Zero(), velocity = Vec3::Zero();
        std::size_t system = noContact;
        Index particle = 0;
    };
    struct SheetHit {
        std::size_t system = noContact;
        Index particle = 0;
        Vec3 change = Vec3::Zero(); // its part of Δa
    };
    struct Term {
        struct Sum {
            Scalar density = 0; // the boundaries' share, its gradient and momentum
            Vec3 gradient = Vec3::Zero(), momentum = Vec3::Zero();
            Scalar densityNow = 0; // the share at x_i
            // the deepest hit of each face (normals more than ~25° apart), up to a corner's three
            SheetContact sheet[maxSheetContacts];
            int sheets = 0;
        };
        static constexpr bool visitsFluid = false;
        static constexpr bool usesGradient = true, usesKernel = true;
        using Particle = Vec3; // the step's displacement x*_i − x_i
        const KernelTable* kernel;
        Scalar dt, distance;
        const Vec3* x;
        const Vec3* predicted;
        Particle particle(std::size_t i) const { return predicted[i] - x[i]; }
        void wall(const Particle& move, const WallPair& q, Sum& sum) const {
            const KernelAtEnd k = kernelAtEnd(*kernel, q, dt);
            sum.density += k.W;
            sum.densityNow += q.mass() * kernel->WSq((q.r - move).squaredNorm());
            sum.gradient += k.gradient;
            if (q.src.moving) sum.momentum += k.W * q.src.v[q.j];
            if (!q.src.normal) return;
            const Vec3& n = q.src.normal[q.j];
            const Vec3 end = q.src.moving ? Vec3(q.r - dt * q.src.v[q.j]) : q.r; // x*_i − x*_b
            const Scalar side = (q.r - move).dot(n) >= 0 ? Scalar(1) : Scalar(-1); // of x_i − x_b
            const Scalar depth = side * end.dot(n) - distance;
            if (!(depth < 0)) return;
            const Scalar footprint = Scalar(2.1) * q.src.surfaceSpacing;
            if ((end - end.dot(n) * n).squaredNorm() > footprint * footprint) return;
            const SheetContact hit{depth, side * n, q.src.moving ? q.src.v[q.j] : Vec3(Vec3::Zero()), q.src.system, q.j};
            // the face of one already hit: the deeper of the two; else a face more, or in place of
            // the shallowest when three are held
            int slot = -1;
            for (int k = 0; k < sum.sheets; ++k)
                if (sum.sheet[k].normal.dot(hit.normal) > Scalar(0.9)) slot = k;
            if (slot < 0 && sum.sheets < maxSheetContacts) {
                sum.sheet[sum.sheets++] = hit;
                return;
            }
            if (slot < 0)
                for (int k = 0; k < sum.sheets; ++k)
                    if (slot < 0 || sum.sheet[k].depth > sum.sheet[slot].depth) slot = k;
            if (hit.depth < sum.sheet[slot].depth) sum.sheet[slot] = hit;
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
    std::vector<Vec3> predicted_, change_, shareChange_, share_;
    std::vector<std::array<SheetHit, maxSheetContacts>> hits_; // (when a boundary is a sheet)
    bool touched_ = false;
};

} // namespace spindrift
