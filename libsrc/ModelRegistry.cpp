#include "ModelRegistry.hpp"

#include "Log.hpp"

#include <boost/dll/shared_library.hpp>
#include <algorithm>
#include <cstdlib>
#include <dlfcn.h>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace spindrift {

struct ModelRegistry::Library {
    boost::dll::shared_library handle;
};

std::string pluginFileName(const std::string& kind, const std::string& name) {
    return "libspindrift_" + kind + "_" + name + ".so";
}

const std::vector<std::string>& ModelRegistry::kinds() {
    static const std::vector<std::string> k{"kernel",   "pressure",         "viscosity", "integrator", "boundary",
                                            "force",    "densityDiffusion", "shifting",  "passive",     "functionObject"};
    return k;
}

ModelRegistry& ModelRegistry::instance() {
    // Never destroyed: plugin code must stay mapped while any model object may exist.
    static ModelRegistry* registry = new ModelRegistry();
    return *registry;
}

namespace {

// The file this code was loaded from (libspindrift.so), "" if unknown. The address is that of a
// function no other library can interpose.
fs::path thisLibrary() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&thisLibrary), &info) != 0 && info.dli_fname != nullptr)
        return info.dli_fname;
    return {};
}

} // namespace

ModelRegistry::ModelRegistry() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("SPINDRIFT_PLUGIN_PATH")) {
        std::stringstream s(env);
        std::string dir;
        while (std::getline(s, dir, ':'))
            if (!dir.empty()) dirs.emplace_back(dir);
    }
    // The plugins beside this library (lib/spindrift/plugins next to lib/libspindrift.so) in
    // the build tree and in any installation, wherever its prefix.
    if (const fs::path core = thisLibrary(); !core.empty())
        dirs.push_back(fs::absolute(core).parent_path() / "spindrift" / "plugins");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) dirs.push_back(exe.parent_path().parent_path() / "lib" / "spindrift" / "plugins");
    for (auto& d : dirs) {
        const fs::path canonical = fs::weakly_canonical(d, ec);
        const fs::path& use = ec ? d : canonical;
        if (std::find(searchPath_.begin(), searchPath_.end(), use) == searchPath_.end())
            searchPath_.push_back(use);
    }
}

void ModelRegistry::prependSearchDirectory(const fs::path& dir) {
    searchPath_.insert(searchPath_.begin(), dir);
}

std::vector<std::string> ModelRegistry::available(const std::string& kind) const {
    std::set<std::string> names;
    const std::string prefix = "libspindrift_" + kind + "_";
    for (const auto& dir : searchPath_) {
        std::error_code ec;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string file = it->path().filename().string();
            if (file.rfind(prefix, 0) == 0 && file.size() > prefix.size() + 3 &&
                file.compare(file.size() - 3, 3, ".so") == 0)
                names.insert(file.substr(prefix.size(), file.size() - prefix.size() - 3));
        }
    }
    for (const auto& l : loaded_)
        if (l.kind == kind) names.insert(l.name);
    return {names.begin(), names.end()};
}

namespace {

std::string describe(const PluginAbiTag& tag) {
    const std::string precision = tag.scalarBytes == 4   ? "single precision (Scalar = float)"
                                  : tag.scalarBytes == 8 ? "double precision (Scalar = double)"
                                                         : "a Scalar of " + std::to_string(tag.scalarBytes) + " bytes";
    return precision + ", interface " + std::to_string(tag.interfaceVersion);
}

// Why the plugin in 'library' cannot be called by this core ("" when its ABI tag is ours). Reads
// data only: nothing in the library runs.
std::string abiMismatch(const boost::dll::shared_library& library, const fs::path& file) {
    std::string builtFor;
    if (library.has("spindrift_abi_tag")) {
        const PluginAbiTag& tag = library.get_alias<const PluginAbiTag>("spindrift_abi_tag");
        if (tag.interfaceVersion == pluginAbiTag.interfaceVersion && tag.scalarBytes == pluginAbiTag.scalarBytes)
            return "";
        builtFor = describe(tag);
    } else if (library.has("spindrift_abi_version")) { // interface 1 exported no precision
        builtFor = "interface " + std::to_string(library.get_alias<const std::uint32_t>("spindrift_abi_version"));
    } else {
        return "";
    }
    return "plugin '" + file.string() + "' was built for " + builtFor + "; this spindrift is " +
           describe(pluginAbiTag) + ": rebuild the plugin against this installation";
}

} // namespace

ModelRegistry::Loaded ModelRegistry::open(const fs::path& file, const SourceLocation& where) const {
    auto library = std::make_shared<Library>();
    try {
        library->handle.load(file.string(), boost::dll::load_mode::rtld_now);
    } catch (const std::exception& e) {
        // A plugin built for another precision or interface often fails here, on a core
        // function whose signature differs: read its ABI tag without binding its code to say so.
        std::string mismatch;
        try {
            const boost::dll::shared_library unbound(file.string(), boost::dll::load_mode::rtld_lazy);
            mismatch = abiMismatch(unbound, file);
        } catch (const std::exception&) {
        }
        if (!mismatch.empty()) throw InputError(where, mismatch);
        throw InputError(where, "cannot load plugin library '" + file.string() + "': " + e.what());
    }
    auto& h = library->handle;
    if (!h.has("spindrift_create") || !h.has("spindrift_kind") || !h.has("spindrift_name") ||
        !(h.has("spindrift_abi_tag") || h.has("spindrift_abi_version")))
        throw InputError(where, "'" + file.string() +
                                    "' is not a Spindrift plugin (it exports no spindrift_create)");
    if (const std::string mismatch = abiMismatch(h, file); !mismatch.empty()) throw InputError(where, mismatch);
    Loaded l{h.get_alias<const char* const>("spindrift_kind"), h.get_alias<const char* const>("spindrift_name"),
             file, library, h.get<void*>("spindrift_create")};
    const auto& known = kinds();
    if (std::find(known.begin(), known.end(), l.kind) == known.end())
        throw InputError(where, "plugin '" + file.string() + "' exports the unknown kind '" + l.kind + "'");
    return l;
}

void ModelRegistry::add(const Loaded& l) {
    loaded_.push_back(l);
    log::info("Loaded " + l.kind + " plugin '" + l.name + "' from " + l.file.string());
}

void ModelRegistry::loadUserLibrary(const std::string& file, const fs::path& baseDir,
                                    const SourceLocation& where) {
    std::vector<fs::path> candidates;
    const fs::path p(file);
    if (p.is_absolute()) candidates.push_back(p);
    else {
        candidates.push_back(baseDir / p);
        for (const auto& dir : searchPath_) candidates.push_back(dir / p);
    }
    for (const auto& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c, ec)) {
            const fs::path canonical = fs::canonical(c);
            for (const auto& l : loaded_)
                if (l.file == canonical) return;
            add(open(canonical, where));
            return;
        }
    }
    throw InputError(where, "cannot find library '" + file + "' (looked in the case directory and " +
                                std::to_string(searchPath_.size()) + " plugin directories)", "libs");
}

std::string ModelRegistry::typeOf(const std::string& kind, const Dictionary& dict) const {
    if (!dict.found("type"))
        throw InputError(dict.where(), "keyword 'type' is missing in " + dict.name() +
                                           " (which " + kind + " model to use)", "type");
    return dict.get<std::string>("type");
}

void* ModelRegistry::factoryFor(const std::string& kind, const std::string& type, const Dictionary& dict) {
    for (const auto& l : loaded_)
        if (l.kind == kind && l.name == type) return l.factory;
    const std::string fileName = pluginFileName(kind, type);
    for (const auto& dir : searchPath_) {
        std::error_code ec;
        const fs::path file = dir / fileName;
        if (!fs::is_regular_file(file, ec)) continue;
        const Loaded l = open(file, dict.locationOf("type"));
        if (l.kind != kind || l.name != type)
            throw InputError(dict.locationOf("type"),
                             "plugin '" + file.string() + "' is the " + l.kind + " '" + l.name + "', not the " +
                                 kind + " '" + type + "' its file name says: build plugins with spindrift_add_plugin",
                             "type");
        add(l);
        return l.factory;
    }
    const auto valid = available(kind);
    std::string list;
    for (const auto& v : valid) list += (list.empty() ? "" : " ") + v;
    std::string message = "Unknown " + kind + " type '" + type + "'. Valid " + kind + " types are: (" + list + ")";
    const std::string suggestion = closestMatch(type, valid);
    if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
    throw InputError(dict.locationOf("type"), message, "type");
}

std::vector<std::string> ModelRegistry::loadedLibraries() const {
    std::vector<std::string> out;
    for (const auto& l : loaded_) out.push_back(l.file.string());
    return out;
}

} // namespace spindrift
