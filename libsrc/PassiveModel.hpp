// Spindrift — models that own a passive particle system (plugins/passive): particles carried by
// the flow that never act on it, such as tracers or the diffuse particles of foam and spray.
// sphSchemes `passive { <name> { type ...; } }`.
//
// In initialise() the model adds its system (Scene::addSystem(name, SystemRole::passive), then
// Scene::registerWithSearch) and declares the neighbours its particles need (e.g.
// search.addInteraction(system, fluid) for the fluid around each); from then on the core searches
// it, writes it (its own block, <name>.vtp, in every time directory), restarts it (its particles
// and every restart field, whatever their number) and rolls it back with the other systems.
// afterStep() moves, creates or deletes its particles once the fluid's step is done, on the
// lists of the step's last search (the particles moved since by at most a step's displacement).
#pragma once

#include "Model.hpp"
#include "Step.hpp"

namespace spindrift {

class PassiveModel : public Model {
public:
    virtual void afterStep(Scene& scene, const Step& step) = 0;
    // A state of its own beyond its particles (e.g. the next id a new particle gets), as the
    // entries of a dictionary: written in every time directory (uniform/passive, a sub-dictionary
    // per model) and given back on a restart from it, after the particles are. "": none.
    virtual std::string stateText() const { return {}; }
    virtual void readState(const Dictionary&) {}
};

} // namespace spindrift
