// Spindrift — run-time selection of models from plugin libraries (Boost.DLL).
//
// A model of kind K named N lives in libspindrift_<K>_<N>.so, found on the plugin path:
// $SPINDRIFT_PLUGIN_PATH (colon-separated), then <dir of libspindrift.so>/spindrift/plugins (the
// build tree's or the installation's, wherever it was installed) and
// <executable>/../lib/spindrift/plugins. Only the libraries a case names are opened; listing the
// valid types reads file names, it opens nothing. User plugins named in controlDict `libs (...)`
// are opened explicitly (looked for in the case directory, the plugin path and LD_LIBRARY_PATH)
// and register the kind and name they export. No file is given to dlopen before its ELF headers
// are checked (unloadableLibrary: a truncated library would kill the process with SIGBUS inside
// dlopen). Before anything in a library is used, its ABI tag (interface version and precision,
// Types.hpp) must equal the core's, and a library found by file name must export that kind and
// name; otherwise it is refused with a message naming the file. Libraries stay loaded until exit.
#pragma once

#include "BoundaryModel.hpp"
#include "DensityDiffusion.hpp"
#include "FunctionObject.hpp"
#include "Integrator.hpp"
#include "Kernel.hpp"
#include "PassiveModel.hpp"
#include "PressureModel.hpp"
#include "ShiftingModel.hpp"
#include "SurfaceTensionModel.hpp"
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

    // kernel pressure viscosity integrator boundary force surfaceTension densityDiffusion shifting passive
    // functionObject
    static const std::vector<std::string>& kinds();

    const std::vector<std::filesystem::path>& searchPath() const { return searchPath_; }
    void prependSearchDirectory(const std::filesystem::path& dir);

    // Opens a user plugin library (controlDict `libs`). A relative name is looked for in
    // userLibraryDirectories(caseDir), as OpenFOAM's `libs` are: "libmyKernel.so", or
    // "myKernel" / "libmyKernel" for it. Errors name 'where' and, for a library not found,
    // every directory looked in.
    void loadUserLibrary(const std::string& file, const std::filesystem::path& caseDir,
                         const SourceLocation& where);
    // The case directory, the plugin search path (SPINDRIFT_PLUGIN_PATH first), then the
    // directories of LD_LIBRARY_PATH.
    std::vector<std::filesystem::path> userLibraryDirectories(const std::filesystem::path& caseDir) const;

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

// Why 'file' must not be given to dlopen ("" when it may): not an ELF shared object of this
// machine's class, byte order and architecture, or cut short — a segment, the program headers or
// the section header table ending past the end of the file (dlopen of a truncated library dies
// of SIGBUS). Reads the headers only.
std::string unloadableLibrary(const std::filesystem::path& file);

} // namespace spindrift
