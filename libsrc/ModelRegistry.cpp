#include "ModelRegistry.hpp"

#include "Log.hpp"

#include <boost/dll/shared_library.hpp>
#include <algorithm>
#include <cstdlib>
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
    static const std::vector<std::string> k{"kernel",     "pressure", "viscosity",     "integrator",
                                                  "boundary",   "force",    "functionObject"};
    return k;
}

ModelRegistry& ModelRegistry::instance() {
    // Never destroyed: plugin code must stay mapped while any model object may exist.
    static ModelRegistry* registry = new ModelRegistry();
    return *registry;
}

ModelRegistry::ModelRegistry() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("SPINDRIFT_PLUGIN_PATH")) {
        std::stringstream s(env);
        std::string dir;
        while (std::getline(s, dir, ':'))
            if (!dir.empty()) dirs.emplace_back(dir);
    }
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) dirs.push_back(exe.parent_path().parent_path() / "lib" / "spindrift" / "plugins");
    dirs.emplace_back(SPINDRIFT_PLUGIN_BUILD_DIR);
    dirs.emplace_back(SPINDRIFT_PLUGIN_INSTALL_DIR);
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

ModelRegistry::Loaded ModelRegistry::open(const fs::path& file, const SourceLocation& where) {
    auto library = std::make_shared<Library>();
    try {
        library->handle.load(file.string(), boost::dll::load_mode::rtld_now);
    } catch (const std::exception& e) {
        throw InputError(where, "cannot load plugin library '" + file.string() + "': " + e.what());
    }
    auto& h = library->handle;
    if (!h.has("spindrift_abi_version") || !h.has("spindrift_create") || !h.has("spindrift_kind") ||
        !h.has("spindrift_name"))
        throw InputError(where, "'" + file.string() +
                                    "' is not a Spindrift plugin (it exports no spindrift_create)");
    const std::uint32_t abi = h.get_alias<const std::uint32_t>("spindrift_abi_version");
    if (abi != pluginAbiVersion)
        throw InputError(where, "plugin '" + file.string() + "' was built against plugin ABI " +
                                    std::to_string(abi) + " but this Spindrift core has ABI " +
                                    std::to_string(pluginAbiVersion) + "; rebuild the plugin");
    Loaded l{h.get_alias<const char* const>("spindrift_kind"),
             h.get_alias<const char* const>("spindrift_name"), file, library};
    loaded_.push_back(l);
    log::info("Loaded " + l.kind + " plugin '" + l.name + "' from " + file.string());
    return l;
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
            open(canonical, where);
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
        if (l.kind == kind && l.name == type)
            return reinterpret_cast<void*>(&l.library->handle.get_alias<Factory<Kernel>>("spindrift_create"));
    const std::string fileName = pluginFileName(kind, type);
    for (const auto& dir : searchPath_) {
        std::error_code ec;
        const fs::path file = dir / fileName;
        if (!fs::is_regular_file(file, ec)) continue;
        const Loaded l = open(file, dict.locationOf("type"));
        if (l.kind != kind || l.name != type)
            throw InputError(dict.locationOf("type"), "plugin file '" + file.string() + "' exports " +
                                                          l.kind + " '" + l.name + "', not " + kind +
                                                          " '" + type + "'", "type");
        return reinterpret_cast<void*>(&l.library->handle.get_alias<Factory<Kernel>>("spindrift_create"));
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
