#include "sweep/filter_config.hpp"

#include "abi/instances.hpp"

#include <stdexcept>

namespace vobench {

std::vector<std::vector<FilterChainItem>> read_filters(const YamlReader& r, const YAML::Node& list, const PluginRegistry& registry) {
    if (!list.IsSequence()) r.fail(list, "filters must be a list of {plugin, params}");
    std::vector<std::vector<FilterChainItem>> chains{{}};
    for (const YAML::Node& item : list) {
        if (!item.IsMap()) r.fail(item, "a filter is {plugin: NAME, params: {...}}");
        r.only_keys(item, {"plugin", "params"}, "a filter");
        FilterChainItem base;
        base.plugin = r.scalar<std::string>(r.required(item, "plugin", "a filter"), "plugin");
        PluginInfo info;
        try {
            info = registry.describe(base.plugin, VOBENCH_KIND_FILTER);
        } catch (const PluginLoadError& e) {
            r.fail(item["plugin"], e.what());
        }
        base.file = info.path;
        base.name = info.name;  // what tables call it, whatever path the config gave
        std::vector<ParamMap> variants{{}};
        if (const YAML::Node params = item["params"]) {
            if (!params.IsMap()) r.fail(params, "params must be a mapping");
            for (const auto& kv : params) {
                const std::string key = kv.first.as<std::string>();
                std::vector<std::string> values;
                if (kv.second.IsSequence()) {
                    if (kv.second.size() == 0) r.fail(kv.second, "a swept filter parameter needs at least one value");
                    for (const YAML::Node& v : kv.second) values.push_back(r.scalar<std::string>(v, "parameter " + key));
                } else {
                    values.push_back(r.scalar<std::string>(kv.second, "parameter " + key));
                }
                for (const std::string& v : values) try {
                        validate_params(info, {{key, v}});
                    } catch (const std::invalid_argument& e) {
                        r.fail(kv.second, e.what());
                    }
                std::vector<ParamMap> next;
                for (const ParamMap& m : variants)
                    for (const std::string& v : values) {
                        ParamMap n = m;
                        n[key] = v;
                        next.push_back(n);
                    }
                variants = std::move(next);
            }
        }
        std::vector<std::vector<FilterChainItem>> next;
        for (const auto& chain : chains)
            for (const ParamMap& m : variants) {
                auto c = chain;
                FilterChainItem f = base;
                f.params = m;
                c.push_back(f);
                next.push_back(c);
            }
        if (next.size() > 10000) r.fail(item, "the filters make more than 10000 chains");
        chains = std::move(next);
    }
    return chains;
}

}  // namespace vobench
