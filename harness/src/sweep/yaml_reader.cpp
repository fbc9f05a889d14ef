#include "sweep/yaml_reader.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace vobench {

namespace {

// Walks the parser's events before any node is built: counts the nodes the document expands to
// (an alias counts as the whole node it names, so a "billion laughs" bomb is refused after a few
// hundred events, not after gigabytes) and refuses a mapping key written twice.
class StructureCheck : public YAML::EventHandler {
public:
    StructureCheck(const YamlReader& reader, uint64_t max_nodes) : reader_(reader), max_nodes_(max_nodes) {}

    void OnDocumentStart(const YAML::Mark&) override {}
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor, nullptr); }
    void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
        const auto it = sizes_.find(anchor);
        add(mark, it == sizes_.end() ? 1 : it->second);
        child_done(mark, nullptr);
    }
    void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string& value) override {
        leaf(mark, anchor, &value);
    }
    void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
        open(mark, anchor, false);
    }
    void OnSequenceEnd() override { close(); }
    void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
        open(mark, anchor, true);
    }
    void OnMapEnd() override { close(); }

private:
    struct Frame {
        bool map = false;
        YAML::anchor_t anchor = 0;
        uint64_t nodes = 1;     // this node and everything below it, aliases expanded
        uint64_t children = 0;  // completed children (in a map: keys and values alternate)
        std::set<std::string> keys;
        YAML::Mark mark;
    };
    [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
        throw ConfigError(fmt::format("{}:{}:{}: {}", reader_.file(), mark.line + 1, mark.column + 1, message));
    }
    void add(const YAML::Mark& mark, uint64_t nodes) {
        total_ += nodes;
        if (!stack_.empty()) stack_.back().nodes += nodes;
        if (total_ > max_nodes_)
            fail(mark, fmt::format("the configuration expands to more than {} nodes (aliases count as copies): refused", max_nodes_));
    }
    void child_done(const YAML::Mark& mark, const std::string* scalar) {
        if (stack_.empty()) return;
        Frame& f = stack_.back();
        if (f.map && f.children % 2 == 0 && scalar != nullptr && !f.keys.insert(*scalar).second)
            fail(mark, "the key '" + *scalar + "' is given twice in this mapping");
        ++f.children;
    }
    void leaf(const YAML::Mark& mark, YAML::anchor_t anchor, const std::string* value) {
        add(mark, 1);
        if (anchor) sizes_[anchor] = 1;
        child_done(mark, value);
    }
    void open(const YAML::Mark& mark, YAML::anchor_t anchor, bool map) {
        add(mark, 1);
        Frame f;
        f.map = map;
        f.anchor = anchor;
        f.mark = mark;
        f.nodes = 1;
        stack_.push_back(std::move(f));
    }
    void close() {
        const Frame f = std::move(stack_.back());
        stack_.pop_back();
        if (f.anchor) sizes_[f.anchor] = f.nodes;
        if (!stack_.empty()) stack_.back().nodes += f.nodes - 1;  // its own node was added when it opened
        child_done(f.mark, nullptr);
    }
    const YamlReader& reader_;
    uint64_t max_nodes_, total_ = 0;
    std::vector<Frame> stack_;
    std::map<YAML::anchor_t, uint64_t> sizes_;
};

}  // namespace

YAML::Node YamlReader::load() const {
    std::ifstream in(file_, std::ios::binary);
    if (!in) throw ConfigError(file_ + ": cannot open file");
    std::string text;
    text.resize(kMaxConfigBytes + 1);
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxConfigBytes) throw ConfigError(fmt::format("{}: larger than {} bytes: refused", file_, kMaxConfigBytes));
    try {
        std::istringstream events(text);
        YAML::Parser parser(events);
        StructureCheck check(*this, kMaxConfigNodes);
        while (parser.HandleNextDocument(check)) {}
        return YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
        throw ConfigError(fmt::format("{}:{}:{}: nested too deeply: refused", file_, e.mark.line + 1, e.mark.column + 1));
    } catch (const YAML::ParserException& e) {
        throw ConfigError(fmt::format("{}:{}:{}: {}", file_, e.mark.line + 1, e.mark.column + 1, e.msg));
    } catch (const YAML::Exception& e) {
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
