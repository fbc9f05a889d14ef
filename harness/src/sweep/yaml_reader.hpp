// yaml_reader.hpp — strict reading of a YAML configuration: every complaint names file, line and
// column (yaml-cpp marks are 0-based; editors count from 1).
#pragma once

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <set>
#include <stdexcept>
#include <string>

namespace vobench {

class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class YamlReader {
public:
    explicit YamlReader(std::string file) : file_(std::move(file)) {}

    // A configuration is small: past these it is refused before anything is built.
    static constexpr std::size_t kMaxConfigBytes = 1 << 20;
    static constexpr uint64_t kMaxConfigNodes = 100000;  // aliases expanded

    // Parses the file; a syntax error, a file over kMaxConfigBytes, a document that expands (aliases
    // counted as copies) to more than kMaxConfigNodes nodes, or a key written twice in one mapping
    // becomes ConfigError("file:line:col: message").
    YAML::Node load() const;
    const std::string& file() const { return file_; }

    std::string where(const YAML::Node& at) const {
        const YAML::Mark m = at.Mark();
        return fmt::format("{}:{}:{}", file_, m.line + 1, m.column + 1);
    }
    [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const { throw ConfigError(where(at) + ": " + message); }
    // Refuses any key outside `allowed`, listing the known ones.
    void only_keys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) const;
    // `node[key]` must exist.
    YAML::Node required(const YAML::Node& map, const std::string& key, const std::string& what) const;

    template <typename T>
    T scalar(const YAML::Node& node, const std::string& what) const {
        if (!node.IsScalar()) fail(node, what + " must be a single value");
        try {
            return node.as<T>();
        } catch (const YAML::Exception&) {
            fail(node, fmt::format("{}: '{}' is not of the expected type", what, node.Scalar()));
        }
    }
    // A scalar or a list of scalars, as strings (e.g. `sensors: kinect1` or `sensors: [kinect1, kinect2]`).
    std::vector<std::string> scalars(const YAML::Node& node, const std::string& what) const;

private:
    std::string file_;
};

}  // namespace vobench
