#include "abi/plugin_probe.hpp"

#include "abi/instances.hpp"
#include "util/files.hpp"
#include "util/hash.hpp"
#include "util/subprocess.hpp"

#include <unistd.h>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>

namespace vobench {
namespace fs = std::filesystem;

namespace {

fs::path cache_folder() {
    if (const char* env = std::getenv("VOBENCH_PROBE_CACHE"); env && *env) return std::string(env) == "off" ? fs::path() : fs::path(env);
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "vobench" / "probes";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "vobench" / "probes";
    return {};
}

// Answers by key: {"info": …} or {"refused": "…"}. The key is the binary's content and this host's
// ABI/API (another vobench may judge the same library differently).
std::mutex g_mutex;
std::map<std::string, nlohmann::json> g_memory;

PluginInfo from_answer(const nlohmann::json& answer, const fs::path& file) {
    if (answer.contains("refused")) throw PluginLoadError(file.string() + ": " + answer["refused"].get<std::string>());
    PluginInfo info = plugin_info_from_json(answer.at("info"));
    info.path = file;  // the same binary may sit at several paths
    return info;
}

int probe_timeout(int timeout_s) {
    if (const char* env = std::getenv("VOBENCH_PROBE_TIMEOUT"); env && std::atoi(env) > 0) return std::atoi(env);
    return timeout_s;
}

// The memo key of a probe: the library's content, and what else the answer depends on.
std::string probe_key(const fs::path& file, const std::string& also) {
    Hasher h;
    try {
        hash_file(h, file);
    } catch (const std::exception&) {
        throw PluginLoadError(file.string() + ": cannot be read");
    }
    h.add(also);
    return h.hex();
}

std::optional<nlohmann::json> remembered(const std::string& key) {
    std::lock_guard<std::mutex> lock(g_mutex);
    if (auto it = g_memory.find(key); it != g_memory.end()) return it->second;
    return std::nullopt;
}

void remember(const std::string& key, const nlohmann::json& answer) {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_memory[key] = answer;
}

// {"refused": "…"} or {"info": <a PluginInfo>}: what a probe child writes when it runs to its end.
bool well_formed(const nlohmann::json& a) {
    if (!a.is_object()) return false;
    if (a.contains("refused")) return a["refused"].is_string();
    try {
        plugin_info_from_json(a.at("info"));
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

// Runs `vobench plugin-probe FILE OUT <extra>` contained, under the timeout; the answer it wrote, or
// null when it wrote none that is well-formed.
nlohmann::json ask_probe_child(const fs::path& file, const std::string& key, const std::vector<std::string>& extra, int timeout_s,
                               ChildResult& child) {
    const fs::path out = fs::temp_directory_path() / ("vobench-probe-" + std::to_string(::getpid()) + "-" + key + "-" +
                                                      std::to_string(std::hash<std::string>{}(file.string())) + ".json");
    std::error_code ec;
    fs::remove(out, ec);
    std::vector<std::string> args = {"plugin-probe", fs::absolute(file).string(), out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    ChildLimits limits;
    limits.timeout_s = timeout_s;
    limits.contain = true;
    limits.memory_mb = 4096;
    child = run_self_limited(args, limits);
    nlohmann::json answer = read_json_or_null(out, 1 << 22);
    fs::remove(out, ec);
    return child.exited && child.exit_code == 0 && well_formed(answer) ? answer : nlohmann::json(nullptr);
}

std::string params_text(const ParamMap& params) {
    std::string text;
    for (const auto& [k, v] : params) text += (text.empty() ? "" : ", ") + k + "=" + v;
    return text;
}

}  // namespace

int probe_plugin_main(const fs::path& file, const fs::path& out, const ParamMap& given, bool extend) {
    nlohmann::json answer;
    try {
        const PluginPtr library = PluginLibrary::load(file);
        PluginInfo info = library->info();
        if (extend && info.has_extra_params) {
            if (info.kind == VOBENCH_KIND_DATASET)
                info = DatasetInstance(library).params_for(given);
            else
                info = OdometryInstance(library).params_for(given);
        }
        answer = {{"info", plugin_info_to_json(info)}};
    } catch (const PluginLoadError& e) {
        // The loader's messages start with the path; the parent adds it back.
        std::string why = e.what();
        if (why.rfind(file.string() + ": ", 0) == 0) why.erase(0, file.string().size() + 2);
        answer = {{"refused", why}};
    } catch (const PluginCallError& e) {
        answer = {{"refused", e.what()}};
    } catch (const std::invalid_argument& e) {
        answer = {{"refused", e.what()}};
    } catch (const std::exception& e) {
        answer = {{"refused", std::string("could not be read: ") + e.what()}};
    }
    write_json_atomic(out, answer);
    std::fflush(nullptr);
    // Not even the plugin's instance destructors: a bridge's interpreter may not end cleanly, and the
    // answer is written.
    ::_exit(0);  // no static destructors of plugin code: they are not part of the descriptor
}

PluginInfo probe_plugin(const fs::path& file, int timeout_s) {
    timeout_s = probe_timeout(timeout_s);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) throw PluginLoadError(file.string() + ": no such file");
    const std::string key =
        probe_key(file, "abi " + std::to_string(VOBENCH_ABI_VERSION) + " api " + std::to_string(VOBENCH_API_VERSION) + " probe 1");
    if (const auto known = remembered(key)) return from_answer(*known, file);
    const fs::path folder = cache_folder();
    nlohmann::json answer = folder.empty() ? nlohmann::json(nullptr) : read_json_or_null(folder / (key + ".json"), 1 << 20);
    if (!well_formed(answer)) {
        ChildResult child;
        answer = ask_probe_child(file, key, {}, timeout_s, child);
        if (answer.is_null()) {
            // A crash or hang while loading is a property of the binary too: cached like a refusal.
            answer = {{"refused", "loading it " + (child.timed_out ? "did not finish within " + std::to_string(timeout_s) + " s (killed)"
                                                                   : "in a child process ended it: " + child.describe())}};
        }
        if (!folder.empty() && !child.timed_out) {  // a hang may be the machine's load: probed again next time
            fs::create_directories(folder, ec);
            try {
                if (!ec) write_json_atomic(folder / (key + ".json"), answer);
            } catch (const std::exception&) {
                // a read-only cache folder only costs a probe next time
            }
        }
    }
    remember(key, answer);
    return from_answer(answer, file);
}

PluginInfo probe_extra_params(const PluginInfo& info, const ParamMap& given, int timeout_s) {
    if (!info.has_extra_params) return info;
    timeout_s = probe_timeout(timeout_s);
    const ParamMap table = table_params(info, given);
    try {
        validate_params(info, table);
    } catch (const std::invalid_argument& e) {
        throw PluginLoadError(e.what());
    }
    std::string also = "extra params of " + fs::absolute(info.path).string();
    std::vector<std::string> extra = {"--extend"};
    for (const auto& [k, v] : table) {
        also += k + "=" + v + ";";
        extra.push_back("--param");
        extra.push_back(k + "=" + v);
    }
    const std::string key = probe_key(info.path, also);
    if (const auto known = remembered(key)) return from_answer(*known, info.path);
    ChildResult child;
    nlohmann::json answer = ask_probe_child(info.path, key, extra, timeout_s, child);
    if (answer.is_null())
        answer = {{"refused", "asking it for the parameters of " + (table.empty() ? std::string("its defaults") : params_text(table)) +
                                  (child.timed_out ? " did not finish within " + std::to_string(timeout_s) + " s (killed)"
                                                   : " in a child process ended it: " + child.describe())}};
    remember(key, answer);
    return from_answer(answer, info.path);
}

}  // namespace vobench
