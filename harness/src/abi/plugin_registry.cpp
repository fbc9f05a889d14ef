#include "abi/plugin_registry.hpp"

#include <boost/dll/runtime_symbol_info.hpp>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>

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

PluginScan PluginRegistry::scan() const {
    PluginScan scan;
    std::set<std::string> seen_names;
    std::set<fs::path> seen_files;
    for (const fs::path& folder : folders_) {
        for (const fs::path& file : candidates(folder)) {
            std::error_code ec;
            const fs::path canonical = fs::weakly_canonical(file, ec);
            if (!seen_files.insert(ec ? file : canonical).second) continue;
            try {
                PluginPtr p = PluginLibrary::load(file);
                if (seen_names.insert(p->name()).second) scan.plugins.push_back(std::move(p));
            } catch (const PluginLoadError& e) {
                scan.refusals.push_back(e.what());
            }
        }
    }
    return scan;
}

std::optional<fs::path> PluginRegistry::locate(const std::string& name) const {
    if (name.find('/') != std::string::npos || fs::path(name).extension() == ".so") {
        if (fs::is_regular_file(name)) return fs::path(name);
        return std::nullopt;
    }
    for (const fs::path& folder : folders_)
        if (fs::is_regular_file(folder / ("vobench_" + name + ".so"))) return folder / ("vobench_" + name + ".so");
    return std::nullopt;
}

PluginPtr PluginRegistry::find(const std::string& name, vobench_plugin_kind kind) const {
    PluginPtr found;
    if (name.find('/') != std::string::npos || fs::path(name).extension() == ".so") {
        found = PluginLibrary::load(name);
    } else {
        for (const fs::path& folder : folders_) {
            // Try the conventional file name first: it avoids loading every library.
            const fs::path guess = folder / ("vobench_" + name + ".so");
            try {
                if (fs::is_regular_file(guess)) {
                    PluginPtr p = PluginLibrary::load(guess);
                    if (p->name() == name) { found = p; break; }
                }
            } catch (const PluginLoadError&) {
                // fall through to the full scan, which reports refusals
            }
        }
        if (!found) {
            for (const PluginPtr& p : scan().plugins)
                if (p->name() == name) { found = p; break; }
        }
        if (!found) {
            std::string searched;
            for (const fs::path& f : folders_) searched += (searched.empty() ? "" : ", ") + f.lexically_normal().string();
            throw PluginLoadError("no plugin named '" + name + "' in " + searched +
                                  " (set VOBENCH_PLUGIN_PATH or pass a path)");
        }
    }
    if (kind != 0 && found->kind() != kind)
        throw PluginLoadError("plugin '" + found->name() + "' is a " + kind_name(found->kind()) + " plugin, not a " +
                              kind_name(kind) + " plugin");
    return found;
}

}  // namespace vobench
