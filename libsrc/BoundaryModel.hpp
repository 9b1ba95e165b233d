// Spindrift — boundary model interface (plugins/boundary).
// initialise() runs once the wall particles exist (e.g. computes their volumes and sets
// system.boundaryMass); update() runs every evaluation after the fluid density is known
// (e.g. to extrapolate wall pressure).
#pragma once

#include "ModelContext.hpp"

namespace spindrift {

class BoundaryModel {
public:
    virtual ~BoundaryModel() = default;
    virtual void initialise(SphSystem& system) = 0;
    virtual void update(SphSystem&) {}
};

} // namespace spindrift
