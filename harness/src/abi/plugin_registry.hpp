// plugin_registry.hpp — where plugins are found.
//
// Search order (first match of a name wins):
//   1. the folders of $VOBENCH_PLUGIN_PATH (':'-separated), so users can override in-tree plugins;
//   2. <exe>/../plugins (the build tree: build/bin/vobench -> build/plugins);
//   3. <exe>/../lib/vobench/plugins (an installed tree).
// Every regular file ending in .so in those folders is a candidate. A NAME that contains a '/' or ends
// in .so is taken as an explicit path instead.
//
// scan() and describe() never run plugin code in this process: they probe in a child
// (abi/plugin_probe.hpp). Only load() does, for the processes that exist to run plugins (a cell's
// child, `vobench track`, the conformance check's child).
#pragma once

#include "abi/plugin_library.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vobench {

struct PluginScan {
    std::vector<PluginInfo> plugins;    // usable, one per name (first in search order)
    std::vector<std::string> refusals;  // one line per file that was refused, crashed or hung
};

class PluginRegistry {
public:
    // Uses the search order above.
    PluginRegistry();
    // Uses exactly these folders (tests).
    explicit PluginRegistry(std::vector<std::filesystem::path> folders);

    const std::vector<std::filesystem::path>& folders() const { return folders_; }

    // Every candidate, probed in child processes (two at a time).
    PluginScan scan() const;
    // The descriptor of a plugin by name (or explicit path) and, when `kind` is not 0, of that kind,
    // probed in a child. Throws PluginLoadError naming what was searched or why it was refused.
    PluginInfo describe(const std::string& name_or_path, vobench_plugin_kind kind = 0) const;
    // Loads the plugin into this process (its code runs here). Throws PluginLoadError.
    PluginPtr load(const std::string& name_or_path, vobench_plugin_kind kind = 0) const;
    // The file a name or path would load, without loading it: an explicit path that exists, or the
    // first <folder>/vobench_<name>.so. Lets callers tell "no such plugin" from "refused to load".
    std::optional<std::filesystem::path> locate(const std::string& name_or_path) const;

private:
    std::vector<std::filesystem::path> folders_;
};

// The folder holding the running executable.
std::filesystem::path executable_dir();

}  // namespace vobench
