// Spindrift — surface tension (plugins/surfaceTension): sphSchemes `surfaceTension { type ...;
// sigma 0.0728; }`, σ the surface tension coefficient [N/m]. A force model (ViscosityModel.hpp's
// ForceModel): the core adds its acceleration to each fluid after the viscosity and the other
// forces, before the pressure model, so iterative pressure solvers predict with it. Every model
// limits the step by the capillary condition (Brackbill, Kothe & Zemach 1992, J. Comput. Phys.
// 100(2), 335–354, doi:10.1016/0021-9991(92)90240-Y, eq. 61):
//   Δt ≤ sqrt(ρ0 Δx³ / (2π σ))
// (capillary waves of the shortest resolved wavelength must not travel more than Δx a step).
#pragma once

#include "ViscosityModel.hpp"

#include <cmath>
#include <numbers>

namespace spindrift {

class SurfaceTensionModel : public ForceModel {
public:
    explicit SurfaceTensionModel(const ModelContext& c) : sigma_(readSigma(c.dict)) {}

    Scalar sigma() const { return sigma_; }

    double maxTimeStep(const Scene& s, const StateSpeeds&) const override {
        return capillaryTimeStepLimit(s.physics.rho0, s.physics.particleSpacing, sigma_);
    }

    static double capillaryTimeStepLimit(double rho0, double dx, double sigma) {
        return sigma > 0 ? std::sqrt(rho0 * dx * dx * dx / (2 * std::numbers::pi * sigma))
                         : std::numeric_limits<double>::infinity();
    }

private:
    static Scalar readSigma(const Dictionary& d) {
        if (!d.found("sigma"))
            throw InputError(d.where(), "surfaceTension needs 'sigma' (the surface tension coefficient, N/m; water in air "
                                        "0.0728)", "sigma");
        const double sigma = d.get<double>("sigma");
        if (!(sigma >= 0)) throw InputError(d.locationOf("sigma"), "sigma must not be negative", "sigma");
        return Scalar(sigma);
    }
    Scalar sigma_;
};

} // namespace spindrift
