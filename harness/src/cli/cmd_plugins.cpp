// vobench plugins list | info | check
#include "abi/conformance.hpp"
#include "abi/plugin_probe.hpp"
#include "abi/plugin_registry.hpp"
#include "cli/commands.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

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

nlohmann::json plugin_json(const PluginInfo& p, bool with_params) {
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(p.path, ec);
    nlohmann::json j{{"name", p.name},       {"kind", kind_name(p.kind)}, {"version", p.version},
                     {"abi", p.abi_version}, {"api", p.api_version},      {"path", (ec ? p.path : canonical).string()}};
    if (with_params) {
        j["description"] = p.description;
        j["license"] = p.license;
        j["url"] = p.url;
        j["params"] = nlohmann::json::array();
        j["has_extra_params"] = p.has_extra_params;
        for (std::size_t k = 0; k < p.params.size(); ++k) {
            const sdk::Param& param = p.params[k];
            nlohmann::json pj{
                {"name", param.name}, {"type", type_name(param.type)}, {"default", param.default_value}, {"help", param.help}};
            if (k >= p.table_size) pj["extra"] = true;  // declared for the values given, not in the descriptor
            if (param.type == VOBENCH_PARAM_INT || param.type == VOBENCH_PARAM_DOUBLE) pj["range"] = {param.min_value, param.max_value};
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
            for (const auto& p : scan.plugins) j.push_back(plugin_json(p, false));
            std::cout << json_text(j) << std::endl;
        } else {
            for (const auto& p : scan.plugins)
                std::cout << fmt::format("{:<9} {:<18} {:<8} {}\n", kind_name(p.kind), p.name, clean_text(p.version),
                                         clean_text(p.description));
            if (scan.plugins.empty()) std::cout << "no plugins found (set VOBENCH_PLUGIN_PATH)\n";
        }
        exit_code = 0;
    });

    auto* info = plugins->add_subcommand("info", "Describe one plugin and its parameters");
    static std::string info_name;
    static bool info_json = false;
    static std::vector<std::string> info_params;
    info->add_option("NAME", info_name, "Plugin name or path")->required();
    info->add_flag("--json", info_json, "Print JSON");
    info->add_option("--param", info_params,
                     "key=value (repeatable): for a plugin whose parameters depend on others' values (e.g. python module=FILE), "
                     "list those it then takes");
    info->callback([&exit_code] {
        const PluginInfo p = probe_extra_params(PluginRegistry().describe(info_name), parse_key_values(info_params, "--param"));
        const nlohmann::json j = plugin_json(p, true);
        if (info_json) {
            std::cout << json_text(j) << std::endl;
        } else {
            std::cout << fmt::format("{} {} ({} plugin, ABI {}, API {}, {})\n{}\n{}\n", p.name, clean_text(p.version), kind_name(p.kind),
                                     p.abi_version, p.api_version, clean_text(p.license), clean_text(p.description, true),
                                     j["path"].get<std::string>());
            if (p.params.empty()) std::cout << "no parameters\n";
            for (std::size_t k = 0; k < p.params.size(); ++k) {
                const sdk::Param& param = p.params[k];
                if (k == p.table_size) std::cout << "declared for the values given (--param):\n";
                std::string range;
                if (param.type == VOBENCH_PARAM_INT || param.type == VOBENCH_PARAM_DOUBLE)
                    range = fmt::format(" [{} .. {}]", param.min_value, param.max_value);
                if (param.type == VOBENCH_PARAM_ENUM) range = " {" + param.choices + "}";
                std::cout << fmt::format("  {:<22} {:<6} = {:<10}{}\n      {}\n", param.name, type_name(param.type),
                                         clean_text(param.default_value), clean_text(range), clean_text(param.help));
            }
            if (p.has_extra_params && p.params.size() == p.table_size)
                std::cout << "(declares more parameters for the values of these: see --param)\n";
        }
        exit_code = 0;
    });

    // Internal: the child that reads one library's descriptor (see abi/plugin_probe.hpp).
    auto* probe = app.add_subcommand("plugin-probe", "")->group("");
    static std::string probe_file, probe_out;
    static std::vector<std::string> probe_params;
    static bool probe_extend = false;
    probe->add_option("file", probe_file)->required();
    probe->add_option("out", probe_out)->required();
    probe->add_flag("--extend", probe_extend);
    probe->add_option("--param", probe_params);
    probe->callback(
        [&exit_code] { exit_code = probe_plugin_main(probe_file, probe_out, parse_key_values(probe_params, "--param"), probe_extend); });

    auto* check = plugins->add_subcommand("check", "Conformance check of a plugin library (in a child process)");
    static ConformanceOptions check_options;
    static std::string check_path, dataset_path;
    static bool in_process = false;
    check->add_option("PATH", check_path, "Plugin library (.so) or the name of an installed plugin")->required();
    check->add_option("--dataset-path", dataset_path, "For dataset plugins: a sequence to open and read");
    static std::vector<std::string> check_params;
    check->add_option("--param", check_params, "key=value (repeatable): parameters (options) for the checked instances");
    check->add_option("--timeout", check_options.timeout_s, "Seconds before a hanging plugin is killed")->capture_default_str();
    check->add_flag("--in-process", in_process, "Run in this process (used by the isolated check itself)");
    check->add_option("--verdict", check_options.verdict_file, "With --in-process: write the verdict here at the very end")->group("");
    check->callback([&exit_code] {
        std::filesystem::path path = check_path;
        if (!std::filesystem::exists(path))
            if (const auto found = PluginRegistry().locate(check_path)) path = *found;  // else the check reports it missing
        check_options.library = path;
        if (!dataset_path.empty()) check_options.dataset_path = dataset_path;
        check_options.params = parse_key_values(check_params, "--param");
        exit_code = in_process ? run_conformance(check_options, std::cout) : check_in_child(check_options, std::cout);
    });
}

}  // namespace vobench::cli
