// Spindrift — what a plugin's factory receives.
#pragma once

#include "Dictionary.hpp"
#include "Scene.hpp"

#include <filesystem>
#include <memory>

namespace spindrift {

struct ModelContext {
    const Dictionary& dict;            // the model's sub-dictionary, e.g. sphSchemes.pressure
    const PhysicalParameters& physics;
    // the scene's constants: the support radius is set before any model is made (the kernel reads
    // it); the rest (particle mass, sound speed, ...) before initialise()
    const SceneConstants& constants;
    const Dictionary* solution = nullptr; // sphSolution's sub-dictionary of the same name, if any
    std::filesystem::path caseDirectory = {}; // the case (function objects write below it)
    std::string name = {};             // the entry's name, e.g. "frontPosition" in functions { }
};

// What a pressure or force model's result is. Every model adds its result to the fluid
// system's acceleration(); it declares what that is:
//   acceleration    a true acceleration (force per mass): every integrator applies it;
//   velocityChange  a change of velocity Δv over the step, added as Δv/Δt (xsph, dfsph);
//   positionChange  a change of position Δx over the step, added as Δx/Δt² (pbf, relaxedPbf).
// The last two are exact only with the integrator the methods are formulated with,
// symplecticEuler (v += Δt a, then x += Δt v); the core refuses other pairings at set-up,
// naming both models (Integrator::applies).
enum class ResultKind { acceleration, velocityChange, positionChange };

// The factory every plugin exports (see Plugin.hpp).
template <class Base> using Factory = std::unique_ptr<Base>(const ModelContext&);

// The kind of model each interface is, as used in plugin file names (libspindrift_<kind>_<name>.so),
// dictionaries and messages. A plugin exports the kind of the base class its factory returns
// (Plugin.hpp), so the ModelRegistry can check it before calling the factory as that type.
template <class Base> struct KindName;
class Kernel;
class PressureModel;
class ViscosityModel;
class Integrator;
class BoundaryModel;
class ExtraForce;
class FunctionObject;
class DensityDiffusion;
class ShiftingModel;
class PassiveModel;
class SurfaceTensionModel;
template <> struct KindName<Kernel> { static constexpr const char* value = "kernel"; };
template <> struct KindName<PressureModel> { static constexpr const char* value = "pressure"; };
template <> struct KindName<ViscosityModel> { static constexpr const char* value = "viscosity"; };
template <> struct KindName<Integrator> { static constexpr const char* value = "integrator"; };
template <> struct KindName<BoundaryModel> { static constexpr const char* value = "boundary"; };
template <> struct KindName<ExtraForce> { static constexpr const char* value = "force"; };
template <> struct KindName<FunctionObject> { static constexpr const char* value = "functionObject"; };
template <> struct KindName<DensityDiffusion> { static constexpr const char* value = "densityDiffusion"; };
template <> struct KindName<ShiftingModel> { static constexpr const char* value = "shifting"; };
template <> struct KindName<PassiveModel> { static constexpr const char* value = "passive"; };
template <> struct KindName<SurfaceTensionModel> { static constexpr const char* value = "surfaceTension"; };

} // namespace spindrift
