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

#include "abi/params.hpp"
#include "abi/plugin_library.hpp"

#include <filesystem>
#include <string>

namespace vobench {

// The descriptor of `file`, probed in a child; throws PluginLoadError("<file>: <reason>") when the
// library is refused, crashes or does not answer within `timeout_s` ($VOBENCH_PROBE_TIMEOUT seconds
// instead, when set).
PluginInfo probe_plugin(const std::filesystem::path& file, int timeout_s = 20);

// `info` (a probe's answer) extended by the parameters its instances declare for the values in `given`
// (API 3 extra_params): a child creates one instance and asks it. Unchanged when the plugin declares
// none. Not cached on disk (what a bridge declares depends on files beside the library, e.g. a Python
// module); memoised in this process by file, library content and the given values. Throws
// PluginLoadError("<plugin>: <reason>") when the values are invalid, or the plugin fails, crashes or
// hangs while answering.
PluginInfo probe_extra_params(const PluginInfo& info, const ParamMap& given, int timeout_s = 60);

// The child side: loads `file` and writes {"info": …} or {"refused": "…"} to `out`; with `given`
// (probe_extra_params) the info is extended by one instance's extra parameters. Returns 0.
int probe_plugin_main(const std::filesystem::path& file, const std::filesystem::path& out, const ParamMap& given = {}, bool extend = false);

}  // namespace vobench
