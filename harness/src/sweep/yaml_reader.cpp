#include "sweep/yaml_reader.hpp"

namespace vobench {

YAML::Node YamlReader::load() const {
    try {
        return YAML::LoadFile(file_);
    } catch (const YAML::BadFile&) {
        throw ConfigError(file_ + ": cannot open file");
    } catch (const YAML::ParserException& e) {
        throw ConfigError(fmt::format("{}:{}:{}: {}", file_, e.mark.line + 1, e.mark.column + 1, e.msg));
    }
}

void YamlReader::only_keys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) const {
    if (!map.IsMap()) fail(map, what + " must be a mapping");
    for (const auto& kv : map) {
        const std::string key = kv.first.as<std::string>();
        if (!allowed.count(key)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            fail(kv.first, fmt::format("unknown key '{}' in {} (known: {})", key, what, list));
        }
    }
}

YAML::Node YamlReader::required(const YAML::Node& map, const std::string& key, const std::string& what) const {
    const YAML::Node n = map[key];
    if (!n) fail(map, fmt::format("{}: the key '{}' is required", what, key));
    return n;
}

std::vector<std::string> YamlReader::scalars(const YAML::Node& node, const std::string& what) const {
    std::vector<std::string> out;
    if (node.IsScalar()) {
        out.push_back(node.Scalar());
    } else if (node.IsSequence() && node.size() > 0) {
        for (const YAML::Node& item : node) out.push_back(scalar<std::string>(item, what));
    } else {
        fail(node, what + " must be a value or a non-empty list");
    }
    return out;
}

}  // namespace vobench
