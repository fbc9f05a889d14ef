// plugin_probe.hpp — reading a plugin's descriptor without running its code in this process.
//
// Loading a library runs its constructors and its entry function, which may crash, hang, print to
// stdout or lie. So the harness (plugins list/info, config validation, vobench run) never loads a
// plugin itself: a child (`vobench plugin-probe FILE OUT`) loads it and writes the descriptor, or the
// refusal, to OUT as JSON; the parent reads it under a timeout. A crash or a hang in the probe is a
// refusal naming what happened. Results are cached by the binary's content hash, in memory and in
// $VOBENCH_PROBE_CACHE (default $XDG_CACHE_HOME/vobench/probes, else ~/.cache/vobench/probes;
// "off" disables the folder), so each build of a plugin is probed once.
#pragma once

#include "abi/plugin_library.hpp"

#include <filesystem>
#include <string>

namespace vobench {

// The descriptor of `file`, probed in a child; throws PluginLoadError("<file>: <reason>") when the
// library is refused, crashes or does not answer within `timeout_s` ($VOBENCH_PROBE_TIMEOUT seconds
// instead, when set).
PluginInfo probe_plugin(const std::filesystem::path& file, int timeout_s = 20);

// The child side: loads `file` and writes {"info": …} or {"refused": "…"} to `out`. Returns 0.
int probe_plugin_main(const std::filesystem::path& file, const std::filesystem::path& out);

}  // namespace vobench
