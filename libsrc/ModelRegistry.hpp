// Spindrift — run-time selection of models from plugin libraries (Boost.DLL).
//
// A model of kind K named N lives in libspindrift_<K>_<N>.so, found on the plugin path:
// $SPINDRIFT_PLUGIN_PATH (colon-separated), then <dir of libspindrift.so>/spindrift/plugins (the
// build tree's or the installation's, wherever it was installed) and
// <executable>/../lib/spindrift/plugins. Only the libraries a case names are opened; listing the
// valid types reads file names, it opens nothing. User plugins named in controlDict `libs (...)`
// are opened explicitly and register the kind and name they export. Before anything in a
// library is used, its ABI tag (interface version and precision, Types.hpp) must equal the
// core's, and a library found by file name must export that kind and name; otherwise it is
// refused with a message naming the file. Libraries stay loaded until exit.
#pragma once

#include "BoundaryModel.hpp"
#include "DensityDiffusion.hpp"
#include "FunctionObject.hpp"
#include "Integrator.hpp"
#include "Kernel.hpp"
#include "PassiveModel.hpp"
#include "PressureModel.hpp"
#include "ShiftingModel.hpp"
#include "ViscosityModel.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace spindrift {

class ModelRegistry {
public:
    // The process-wide registry (libraries it opened stay loaded until exit).
    static ModelRegistry& instance();

    // kernel pressure viscosity integrator boundary force densityDiffusion shifting passive functionObject
    static const std::vector<std::string>& kinds();

    const std::vector<std::filesystem::path>& searchPath() const { return searchPath_; }
    void prependSearchDirectory(const std::filesystem::path& dir);

    // Opens a user plugin library (controlDict `libs`); relative paths are tried against
    // 'baseDir' and then the search path. Errors name 'where'.
    void loadUserLibrary(const std::string& file, const std::filesystem::path& baseDir,
                         const SourceLocation& where);

    // Valid type names of a kind (from file names on the search path + user libraries).
    std::vector<std::string> available(const std::string& kind) const;

    // Creates the model named by `type` in 'dict' (a sub-dictionary such as
    // sphSchemes.pressure). Unknown type -> InputError at the `type` entry:
    // "Unknown pressure type 'pcsph'. Valid pressure types are: (...)".
    template <class Base>
    std::unique_ptr<Base> create(const Dictionary& dict, const PhysicalParameters& physics, const SceneConstants& constants,
                                 const Dictionary* solution = nullptr,
                                 const std::filesystem::path& caseDirectory = {}, const std::string& name = {}) {
        const std::string kind = KindName<Base>::value;
        const std::string type = typeOf(kind, dict);
        // factoryFor returns only the factory of a library exporting this kind, and a plugin's
        // exported kind is that of its factory's base class (Plugin.hpp): it is a Factory<Base>.
        auto factory = reinterpret_cast<Factory<Base>*>(factoryFor(kind, type, dict));
        ModelContext context{dict, physics, constants, solution, caseDirectory, name};
        auto model = factory(context);
        dict.checkAllKeywordsUsed();
        return model;
    }

    // Paths of the libraries opened so far, in order.
    std::vector<std::string> loadedLibraries() const;

private:
    ModelRegistry();
    std::string typeOf(const std::string& kind, const Dictionary& dict) const;
    // The address of the factory of the `kind` model `type`, from a library that exports that
    // kind and name (opened now if needed); InputError at dict's `type` otherwise.
    void* factoryFor(const std::string& kind, const std::string& type, const Dictionary& dict);
    struct Library;
    struct Loaded {
        std::string kind, name;
        std::filesystem::path file;
        std::shared_ptr<Library> library;
        void* factory = nullptr; // spindrift_create: a Factory<Base> for the Base of `kind`
    };
    // Loads 'file' and checks that it is a plugin of this core's ABI and of a known kind (not
    // registered yet). Errors name 'where'.
    Loaded open(const std::filesystem::path& file, const SourceLocation& where) const;
    void add(const Loaded& library);

    std::vector<std::filesystem::path> searchPath_;
    std::vector<Loaded> loaded_;
};

std::string pluginFileName(const std::string& kind, const std::string& name);

} // namespace spindrift
