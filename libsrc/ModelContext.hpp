// Spindrift — what a plugin's factory receives.
#pragma once

#include "Dictionary.hpp"
#include "SphSystem.hpp"

#include <filesystem>
#include <memory>

namespace spindrift {

struct ModelContext {
    const Dictionary& dict;            // the model's sub-dictionary, e.g. sphSchemes.pressure
    const PhysicalParameters& physics;
    const Dictionary* solution = nullptr; // sphSolution's sub-dictionary of the same name, if any
    std::filesystem::path caseDirectory = {}; // the case (function objects write below it)
    std::string name = {};             // the entry's name, e.g. "frontPosition" in functions { }
};

// The factory every plugin exports (see Plugin.hpp).
template <class Base> using Factory = std::unique_ptr<Base>(const ModelContext&);

// Kind names as used in plugin file names, dictionaries and messages (ModelRegistry.hpp).
template <class Base> struct KindName;

} // namespace spindrift
