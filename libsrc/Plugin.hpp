// Spindrift — how a model becomes a plugin library.
//
// In the plugin's .cpp, after the class:
//     SPINDRIFT_PLUGIN(PressureModel, "pressure", "wcsph", Wcsph)
// builds a factory `std::unique_ptr<PressureModel>(const ModelContext&)` and exports, with
// BOOST_DLL_ALIAS, the symbols the ModelRegistry reads: the factory, the plugin's kind and
// name, and the core's plugin ABI version it was compiled against. The library file must be
// named libspindrift_<kind>_<name>.so (cmake: spindrift_add_plugin(<kind> <name> ...)).
#pragma once

#include "ModelContext.hpp"

#include <boost/dll/alias.hpp>
#include <memory>

#define SPINDRIFT_PLUGIN(Base, kindString, nameString, Class)                                      \
    namespace spindrift_plugin_exports {                                                           \
    std::unique_ptr<::spindrift::Base> create(const ::spindrift::ModelContext& context) {          \
        return std::make_unique<Class>(context);                                                   \
    }                                                                                              \
    const char* const kind = kindString;                                                           \
    const char* const name = nameString;                                                           \
    const std::uint32_t abiVersion = ::spindrift::pluginAbiVersion;                                \
    }                                                                                              \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::create, spindrift_create)                            \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::kind, spindrift_kind)                                \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::name, spindrift_name)                                \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::abiVersion, spindrift_abi_version)
