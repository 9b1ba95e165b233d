// Spindrift — boundary model interface (plugins/boundary): how the particles of boundary systems
// (walls and bodies) act on the fluid. initialise() runs once every system exists, before the
// pressure model's: it gives each boundary its particles' masses M_b and says whether it mirrors
// the fluid's pressure or has its own (ParticleSystem::mass, pressureMirrored, viscousVelocity).
// update() runs at every evaluation once the fluids' density and pressure are known (after
// computeDensity), e.g. to extrapolate the boundaries' pressure; a pressure solver that changes
// a fluid's pressure in its iterations has the core carry the change to the boundaries
// (StepServices::updateBoundaryPressure, which calls updatePressure). correctAcceleration() runs
// last, after the pressure and shifting models, when a fluid's accelerations and shift are
// complete: there every boundary
// model applies the collision of fluid particles that the step would carry into a boundary
// (WallCollision.hpp, the model dictionary's `collision { }`; on at the faces by default,
// `collision no;` off) and reports the force that puts on each boundary (addReactions, right
// after it, when something wants the reactions). A model reads its collision in its constructor
// and initialises it in initialise().
#pragma once

#include "Model.hpp"
#include "PairLoop.hpp"
#include "Scene.hpp"
#include "Step.hpp"
#include "WallCollision.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace spindrift {

class BoundaryModel : public Model {
public:
    void initialise(Scene& scene) override = 0;
    virtual void update(Scene&, const Step&) {}
    // The boundaries' own pressure from pressure p of 'fluid' (no-op for mirrored boundaries).
    virtual void updatePressure(Scene&, const ParticleSystem& /*fluid*/, const std::vector<Scalar>& /*p*/) {}
    virtual void correctAcceleration(Scene& s, ParticleSystem& fluid, const Step& step) { collision_.apply(s, fluid, step.dt); }
    virtual void addReactions(const Scene& s, const ParticleSystem& fluid, const Step& step, Reactions& r) const {
        collision_.addReactions(s, fluid, step.dt, r);
    }

protected:
    // Σ f(x, z) over the midpoint grid of spacing dx/32 that covers the plane's disc of radius
    // R (a line in 2D, z = 0): a plane integral over its element, for the single layer's volume
    // factors (adami's, akinci's), in which the element cancels.
    template <class F>
    static double planeSum(double R, int dim, double dx, F&& f) {
        const double e = dx / 32;
        const int m = int(std::ceil(R / e)), mz = dim == 3 ? m : 0;
        double sum = 0;
        for (int j = -m; j < m; ++j)
            for (int l = -mz; l < std::max(mz, 1); ++l) sum += f((j + 0.5) * e, dim == 3 ? (l + 0.5) * e : 0.0);
        return sum;
    }

    // Σ_k W_bk over the particles k of every boundary (b's own included) for each particle b of
    // 'wall': the neighbourhood of Akinci et al.'s (2012) adaptive volume V_b = 1/Σ_k W_bk.
    static std::vector<Scalar> boundaryKernelSums(const Scene& s, const ParticleSystem& wall) {
        const auto& kt = s.kernel;
        std::vector<Scalar> sum(wall.size(), kt.W0());
        const auto& x = wall.particles.position();
        for (const ParticleSystem* other : s.boundaries()) {
            const NeighbourList list = s.search.listBetween(wall.index, other->index);
            const auto& xl = other->particles.position();
            forEachIndex(x.size(), [&](std::size_t b) {
                forEachNeighbour(list, x, xl, b, [&](Index, const Vec3&, Scalar r2) { sum[b] += kt.WSq(r2); });
            });
        }
        return sum;
    }
    // A wall's own neighbourhoods: the largest Σ_k W_bk over its particles (the lattice's sum when
    // the wall covers the support), and whether its particles see their neighbours in a sheet
    // (a surface sampled in one layer): the second moment C = Σ_k W_bk r_bk ⊗ r_bk of most
    // neighbourhoods nearly singular, det C < 0.1 (tr C/d)^d (zero where a sheet is flat, 1 for
    // an isotropic neighbourhood; on a lattice of two layers or more every particle's is far
    // above 0.1; a sheet's edges and corners, where two faces meet, are not flat).
    struct Neighbourhood {
        Scalar fullest = 0;
        bool sheet = false;
    };
    static Neighbourhood ownNeighbourhood(const Scene& s, const ParticleSystem& wall) {
        const auto& kt = s.kernel;
        const int dim = s.physics.dimension;
        const NeighbourList list = s.search.listBetween(wall.index, wall.index);
        const auto& x = wall.particles.position();
        std::vector<Scalar> sum(x.size(), kt.W0());
        std::vector<char> flat(x.size(), 0);
        forEachIndex(x.size(), [&](std::size_t b) {
            Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
            forEachNeighbour(list, x, x, b, [&](Index, const Vec3& r, Scalar r2) {
                const Scalar W = kt.WSq(r2);
                sum[b] += W;
                const Eigen::Vector3d d = r.cast<double>();
                c += double(W) * d * d.transpose();
            });
            const double trace = c.topLeftCorner(dim, dim).trace() / dim;
            const double det = dim == 3 ? c.determinant() : c.topLeftCorner<2, 2>().determinant();
            flat[b] = trace > 0 && det < 0.1 * std::pow(trace, dim);
        });
        Neighbourhood n;
        if (!x.empty()) n.fullest = *std::max_element(sum.begin(), sum.end());
        n.sheet = 2 * std::size_t(std::count(flat.begin(), flat.end(), 1)) > x.size();
        return n;
    }
    WallCollision collision_;
};

} // namespace spindrift
