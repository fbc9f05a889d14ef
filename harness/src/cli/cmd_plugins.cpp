// vobench plugins list | info | check
#include "abi/conformance.hpp"
#include "abi/plugin_registry.hpp"
#include "cli/commands.hpp"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <iostream>

namespace vobench::cli {
namespace {

const char* type_name(vobench_param_type t) {
    switch (t) {
    case VOBENCH_PARAM_BOOL: return "bool";
    case VOBENCH_PARAM_INT: return "int";
    case VOBENCH_PARAM_DOUBLE: return "double";
    case VOBENCH_PARAM_STRING: return "string";
    case VOBENCH_PARAM_ENUM: return "enum";
    default: return "?";
    }
}

nlohmann::json plugin_json(const PluginLibrary& p, bool with_params) {
    const vobench_plugin_descriptor& d = p.descriptor();
    nlohmann::json j{{"name", d.name},
                     {"kind", kind_name(d.kind)},
                     {"version", d.version},
                     {"abi", d.abi_version},
                     {"api", d.api_version},
                     {"path", std::filesystem::weakly_canonical(p.path()).string()}};
    if (with_params) {
        j["description"] = d.description;
        j["license"] = d.license;
        j["url"] = d.url ? d.url : "";
        j["params"] = nlohmann::json::array();
        for (const sdk::Param& param : p.params()) {
            nlohmann::json pj{{"name", param.name}, {"type", type_name(param.type)}, {"default", param.default_value},
                              {"help", param.help}};
            if (param.type == VOBENCH_PARAM_INT || param.type == VOBENCH_PARAM_DOUBLE)
                pj["range"] = {param.min_value, param.max_value};
            if (param.type == VOBENCH_PARAM_ENUM) pj["choices"] = param.choices;
            j["params"].push_back(pj);
        }
    }
    return j;
}

}  // namespace

void add_plugins_commands(CLI::App& app, int& exit_code) {
    CLI::App* plugins = app.add_subcommand("plugins", "List, describe and check plugins");
    plugins->require_subcommand(1);

    auto* list = plugins->add_subcommand("list", "List the plugins found on the search path");
    static bool list_json = false;
    list->add_flag("--json", list_json, "Print a JSON array");
    list->callback([&exit_code] {
        const PluginRegistry registry;
        const PluginScan scan = registry.scan();
        for (const std::string& refusal : scan.refusals) spdlog::warn("refused {}", refusal);
        if (list_json) {
            nlohmann::json j = nlohmann::json::array();
            for (const auto& p : scan.plugins) j.push_back(plugin_json(*p, false));
            std::cout << j.dump(2) << std::endl;
        } else {
            for (const auto& p : scan.plugins)
                std::cout << fmt::format("{:<9} {:<16} {:<8} {}\n", kind_name(p->kind()), p->name(),
                                         p->descriptor().version, p->descriptor().description);
            if (scan.plugins.empty()) std::cout << "no plugins found (set VOBENCH_PLUGIN_PATH)\n";
        }
        exit_code = 0;
    });

    auto* info = plugins->add_subcommand("info", "Describe one plugin and its parameters");
    static std::string info_name;
    static bool info_json = false;
    info->add_option("NAME", info_name, "Plugin name or path")->required();
    info->add_flag("--json", info_json, "Print JSON");
    info->callback([&exit_code] {
        const PluginPtr p = PluginRegistry().find(info_name);
        const nlohmann::json j = plugin_json(*p, true);
        if (info_json) {
            std::cout << j.dump(2) << std::endl;
        } else {
            std::cout << fmt::format("{} {} ({} plugin, ABI {}, API {}, {})\n{}\n{}\n", p->name(), p->descriptor().version,
                                     kind_name(p->kind()), p->descriptor().abi_version, p->descriptor().api_version,
                                     p->descriptor().license, p->descriptor().description, j["path"].get<std::string>());
            if (p->params().empty()) std::cout << "no parameters\n";
            for (const sdk::Param& param : p->params()) {
                std::string range;
                if (param.type == VOBENCH_PARAM_INT || param.type == VOBENCH_PARAM_DOUBLE)
                    range = fmt::format(" [{} .. {}]", param.min_value, param.max_value);
                if (param.type == VOBENCH_PARAM_ENUM) range = " {" + param.choices + "}";
                std::cout << fmt::format("  {:<22} {:<6} = {:<10}{}\n      {}\n", param.name, type_name(param.type),
                                         param.default_value, range, param.help);
            }
        }
        exit_code = 0;
    });

    auto* check = plugins->add_subcommand("check", "Conformance check of a plugin library (in a child process)");
    static ConformanceOptions check_options;
    static std::string check_path, dataset_path;
    static bool in_process = false;
    check->add_option("PATH", check_path, "Plugin library (.so) or the name of an installed plugin")->required();
    check->add_option("--dataset-path", dataset_path, "For dataset plugins: a sequence to open and read");
    check->add_option("--timeout", check_options.timeout_s, "Seconds before a hanging plugin is killed")->capture_default_str();
    check->add_flag("--in-process", in_process, "Run in this process (used by the isolated check itself)");
    check->callback([&exit_code] {
        std::filesystem::path path = check_path;
        if (!std::filesystem::exists(path)) {
            try {
                path = PluginRegistry().find(check_path)->path();
            } catch (const PluginLoadError&) {
                // keep the path: the check reports it as missing
            }
        }
        check_options.library = path;
        if (!dataset_path.empty()) check_options.dataset_path = dataset_path;
        exit_code = in_process ? run_conformance(check_options, std::cout) : check_in_child(check_options, std::cout);
    });
}

}  // namespace vobench::cli
