#include "abi/plugin_registry.hpp"

#include "abi/plugin_probe.hpp"

#include <boost/dll/runtime_symbol_info.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <set>
#include <sstream>
#include <thread>

namespace vobench {
namespace fs = std::filesystem;

fs::path executable_dir() { return fs::path(boost::dll::program_location().parent_path().string()); }

PluginRegistry::PluginRegistry() {
    if (const char* env = std::getenv("VOBENCH_PLUGIN_PATH")) {
        std::stringstream ss(env);
        std::string item;
        while (std::getline(ss, item, ':'))
            if (!item.empty()) folders_.emplace_back(item);
    }
    const fs::path exe = executable_dir();
    folders_.push_back(exe / ".." / "plugins");
    folders_.push_back(exe / ".." / "lib" / "vobench" / "plugins");
}

PluginRegistry::PluginRegistry(std::vector<fs::path> folders) : folders_(std::move(folders)) {}

namespace {
std::vector<fs::path> candidates(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec) && it->path().extension() == ".so") files.push_back(it->path());
    std::sort(files.begin(), files.end());  // a stable order, whatever the file system's
    return files;
}
}  // namespace

namespace {

bool is_explicit_path(const std::string& name) { return name.find('/') != std::string::npos || fs::path(name).extension() == ".so"; }

void check_kind(const PluginInfo& info, vobench_plugin_kind kind) {
    if (kind != 0 && info.kind != kind)
        throw PluginLoadError("plugin '" + info.name + "' is a " + kind_name(info.kind) + " plugin, not a " + kind_name(kind) + " plugin");
}

}  // namespace

PluginScan PluginRegistry::scan() const {
    std::vector<fs::path> files;
    std::set<fs::path> seen_files;
    for (const fs::path& folder : folders_)
        for (const fs::path& file : candidates(folder)) {
            std::error_code ec;
            const fs::path canonical = fs::weakly_canonical(file, ec);
            if (seen_files.insert(ec ? file : canonical).second) files.push_back(file);
        }
    // Probed two at a time (a probe is mostly waiting for a child's start-up).
    std::vector<std::optional<PluginInfo>> infos(files.size());
    std::vector<std::string> refusals(files.size());
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i; (i = next++) < files.size();) {
            try {
                infos[i] = probe_plugin(files[i]);
            } catch (const PluginLoadError& e) {
                refusals[i] = e.what();
            }
        }
    };
    std::thread helper(worker);
    worker();
    helper.join();
    PluginScan scan;
    std::set<std::string> seen_names;
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (!refusals[i].empty())
            scan.refusals.push_back(refusals[i]);
        else if (infos[i] && seen_names.insert(infos[i]->name).second)
            scan.plugins.push_back(*infos[i]);
    }
    return scan;
}

std::optional<fs::path> PluginRegistry::locate(const std::string& name) const {
    if (is_explicit_path(name)) {
        if (fs::is_regular_file(name)) return fs::path(name);
        return std::nullopt;
    }
    for (const fs::path& folder : folders_)
        if (fs::is_regular_file(folder / ("vobench_" + name + ".so"))) return folder / ("vobench_" + name + ".so");
    return std::nullopt;
}

PluginInfo PluginRegistry::describe(const std::string& name, vobench_plugin_kind kind) const {
    if (is_explicit_path(name)) {
        PluginInfo info = probe_plugin(name);
        check_kind(info, kind);
        return info;
    }
    // The conventional file name first: it avoids probing every library.
    std::optional<std::string> refusal;
    for (const fs::path& folder : folders_) {
        const fs::path guess = folder / ("vobench_" + name + ".so");
        if (!fs::is_regular_file(guess)) continue;
        try {
            PluginInfo info = probe_plugin(guess);
            if (info.name == name) {
                check_kind(info, kind);
                return info;
            }
        } catch (const PluginLoadError& e) {
            if (!refusal) refusal = e.what();  // the file that should be the plugin is refused: say why
        }
    }
    for (const PluginInfo& info : scan().plugins)
        if (info.name == name) {
            check_kind(info, kind);
            return info;
        }
    if (refusal) throw PluginLoadError(*refusal);
    std::string searched;
    for (const fs::path& f : folders_) searched += (searched.empty() ? "" : ", ") + f.lexically_normal().string();
    throw PluginLoadError("no plugin named '" + name + "' in " + searched + " (set VOBENCH_PLUGIN_PATH or pass a path)");
}

PluginPtr PluginRegistry::load(const std::string& name, vobench_plugin_kind kind) const {
    PluginPtr found;
    if (is_explicit_path(name)) {
        found = PluginLibrary::load(name);
    } else {
        const std::optional<fs::path> guess = locate(name);
        if (guess) {
            try {
                PluginPtr p = PluginLibrary::load(*guess);
                if (p->name() == name) found = p;
            } catch (const PluginLoadError&) {
                // fall back to the search below, which names what was searched
            }
        }
        if (!found) found = PluginLibrary::load(describe(name, kind).path);
    }
    check_kind(found->info(), kind);
    return found;
}

}  // namespace vobench
