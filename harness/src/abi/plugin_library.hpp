// plugin_library.hpp — one loaded plugin library and its validated descriptor.
//
// Loading goes through Boost.DLL. A library is refused, with a one-line reason and never a crash, when
// it cannot be opened, exports no vobench_plugin_entry_v1 (the reason names any other generation it
// does export), returns no descriptor, or returns a malformed one (see validate_descriptor()).
// The library stays loaded as long as any shared_ptr to it lives: instances hold one.
#pragma once

#include <vobench/vobench_plugin.h>
#include <vobench/plugin.hpp>

#include <boost/dll/shared_library.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vobench {

class PluginLoadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The reason a descriptor is unusable by this host, or "" when it is fine. Pure: used by the loader
// and by the conformance check.
std::string validate_descriptor(const vobench_plugin_descriptor* d);

// "dataset" / "odometry" / "unknown".
const char* kind_name(vobench_plugin_kind kind);

// A descriptor copied out of a library: plain values that stay valid after the library is gone, and
// that a probe in a child process can hand back (abi/plugin_probe.hpp). Every string is valid UTF-8
// (invalid bytes replaced): it came from plugin code.
struct PluginInfo {
    std::filesystem::path path;
    std::string name, version, description, license, url;
    vobench_plugin_kind kind = 0;
    uint32_t abi_version = 0, api_version = 0;
    std::vector<sdk::Param> params;
    // API 3: the plugin's instances declare parameters beyond the descriptor's table, which depend on
    // the values of some of its own (extra_params). `params` then holds the descriptor's table first
    // (`table_size` rows) and, once extended for given values (abi/plugin_probe.hpp
    // probe_extra_params, or an instance's own), the extra parameters after it.
    bool has_extra_params = false;
    std::size_t table_size = 0;
};

// Whether a parameter-table row set, read from plugin code, follows the ABI's rules (identifiers,
// unique also against `taken`, known types, valid defaults); "" or the first reason it does not.
std::string check_param_table(uint32_t count, const vobench_param_desc* params, const std::vector<std::string>& taken = {});
// The rows of such a table as SDK values, their texts cleaned.
std::vector<sdk::Param> params_of_table(uint32_t count, const vobench_param_desc* params);

nlohmann::json plugin_info_to_json(const PluginInfo& info);
PluginInfo plugin_info_from_json(const nlohmann::json& j);  // throws nlohmann::json::exception when malformed

class PluginLibrary {
public:
    // Loads and validates; throws PluginLoadError("<path>: <reason>").
    static std::shared_ptr<const PluginLibrary> load(const std::filesystem::path& path);

    const vobench_plugin_descriptor& descriptor() const { return *descriptor_; }
    const std::filesystem::path& path() const { return path_; }
    const PluginInfo& info() const { return info_; }
    const std::string& name() const { return info_.name; }
    vobench_plugin_kind kind() const { return descriptor_->kind; }
    // The parameter table as SDK values (used for validation and `plugins info`).
    const std::vector<sdk::Param>& params() const { return info_.params; }
    // The entry function, for the conformance check.
    vobench_plugin_entry_fn entry() const { return entry_; }

private:
    PluginLibrary() = default;
    boost::dll::shared_library library_;
    std::filesystem::path path_;
    vobench_plugin_entry_fn entry_ = nullptr;
    const vobench_plugin_descriptor* descriptor_ = nullptr;
    PluginInfo info_;
};

using PluginPtr = std::shared_ptr<const PluginLibrary>;

}  // namespace vobench
