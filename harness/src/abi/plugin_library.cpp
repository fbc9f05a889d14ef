#include "abi/plugin_library.hpp"

#include "util/escape.hpp"

#include <cctype>
#include <cmath>
#include <cstddef>
#include <set>

namespace vobench {
namespace {

// The smallest struct sizes this host accepts: everything up to the last member of API 1.
constexpr std::size_t kMinDescriptorSize = offsetof(vobench_plugin_descriptor, odometry) + sizeof(void*);
constexpr std::size_t kMinParamSize = offsetof(vobench_param_desc, help) + sizeof(const char*);
constexpr std::size_t kMinDatasetApiSize = offsetof(vobench_dataset_api, destroy) + sizeof(void*);
constexpr std::size_t kMinOdometryApiSize = offsetof(vobench_odometry_api, destroy) + sizeof(void*);
constexpr std::size_t kMinFilterApiSize = offsetof(vobench_filter_api, destroy) + sizeof(void*);

bool is_identifier(const char* s) {
    if (s == nullptr || *s == '\0') return false;
    for (; *s; ++s)
        if (!(std::islower(static_cast<unsigned char>(*s)) || std::isdigit(static_cast<unsigned char>(*s)) || *s == '_')) return false;
    return true;
}

// One parameter-table row as SDK values; the texts cleaned (they came from plugin code).
sdk::Param param_of(const vobench_param_desc& p) {
    return {p.name,
            p.type,
            clean_text(p.default_value),
            p.min_value,
            p.max_value,
            p.choices ? clean_text(p.choices) : "",
            p.help ? clean_text(p.help) : ""};
}

}  // namespace

std::string check_param_table(uint32_t count, const vobench_param_desc* params, const std::vector<std::string>& taken) {
    if (count == 0) return "";
    if (params == nullptr) return "param_count is " + std::to_string(count) + " but params is NULL";
    if (count > 4096) return "param_count is " + std::to_string(count) + " (at most 4096)";
    if (params->struct_size < kMinParamSize)
        return "parameter table struct_size " + std::to_string(params->struct_size) + " is smaller than " + std::to_string(kMinParamSize);
    std::set<std::string> names(taken.begin(), taken.end());
    for (uint32_t i = 0; i < count; ++i) {
        const vobench_param_desc* p = VOBENCH_ARRAY_AT(params, vobench_param_desc, i);
        const std::string where = "parameter #" + std::to_string(i);
        if (p->struct_size != params->struct_size) return where + ": struct_size differs from the first entry's";
        if (!is_identifier(p->name)) return where + ": name is not an identifier [a-z0-9_]+";
        if (!names.insert(p->name).second) return std::string("parameter '") + p->name + "' is declared twice";
        if (p->type < VOBENCH_PARAM_BOOL || p->type > VOBENCH_PARAM_ENUM)
            return std::string("parameter '") + p->name + "': unknown type " + std::to_string(p->type);
        if (p->default_value == nullptr) return std::string("parameter '") + p->name + "': no default value";
        if (p->type == VOBENCH_PARAM_ENUM && (p->choices == nullptr || *p->choices == '\0'))
            return std::string("parameter '") + p->name + "': enum without choices";
        if ((p->type == VOBENCH_PARAM_INT || p->type == VOBENCH_PARAM_DOUBLE) && !(p->min_value <= p->max_value))
            return std::string("parameter '") + p->name + "': min_value > max_value";
        const sdk::Param sp = param_of(*p);
        const std::string why = sdk::check_param_value(sp, sp.default_value);
        if (!why.empty()) return std::string("parameter '") + p->name + "': default " + why;
    }
    return "";
}

std::vector<sdk::Param> params_of_table(uint32_t count, const vobench_param_desc* params) {
    std::vector<sdk::Param> out;
    for (uint32_t i = 0; i < count; ++i) out.push_back(param_of(*VOBENCH_ARRAY_AT(params, vobench_param_desc, i)));
    return out;
}

namespace {
// JSON has no infinity: an unbounded range travels as the string "inf" / "-inf".
nlohmann::json bound_to_json(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(v > 0 ? "inf" : v < 0 ? "-inf" : "nan");
}
double bound_from_json(const nlohmann::json& v) {
    if (v.is_number()) return v.get<double>();
    const std::string s = v.get<std::string>();
    return s == "inf" ? HUGE_VAL : s == "-inf" ? -HUGE_VAL : std::nan("");
}
}  // namespace

nlohmann::json plugin_info_to_json(const PluginInfo& i) {
    nlohmann::json params = nlohmann::json::array();
    for (const sdk::Param& p : i.params)
        params.push_back({{"name", p.name},
                          {"type", p.type},
                          {"default", p.default_value},
                          {"min", bound_to_json(p.min_value)},
                          {"max", bound_to_json(p.max_value)},
                          {"choices", p.choices},
                          {"help", p.help}});
    return {{"path", i.path.string()},
            {"name", i.name},
            {"version", i.version},
            {"description", i.description},
            {"license", i.license},
            {"url", i.url},
            {"kind", i.kind},
            {"abi_version", i.abi_version},
            {"api_version", i.api_version},
            {"params", params},
            {"has_extra_params", i.has_extra_params},
            {"table_size", i.table_size}};
}

PluginInfo plugin_info_from_json(const nlohmann::json& j) {
    PluginInfo i;
    i.path = j.at("path").get<std::string>();
    i.name = j.at("name");
    i.version = j.at("version");
    i.description = j.at("description");
    i.license = j.at("license");
    i.url = j.at("url");
    i.kind = j.at("kind");
    i.abi_version = j.at("abi_version");
    i.api_version = j.at("api_version");
    for (const auto& p : j.at("params"))
        i.params.push_back({p.at("name"), p.at("type"), p.at("default"), bound_from_json(p.at("min")), bound_from_json(p.at("max")),
                            p.at("choices"), p.at("help")});
    i.has_extra_params = j.value("has_extra_params", false);
    i.table_size = j.value("table_size", i.params.size());
    if (i.table_size > i.params.size()) throw std::out_of_range("table_size exceeds the parameter count");
    return i;
}

const char* kind_name(vobench_plugin_kind kind) {
    switch (kind) {
        case VOBENCH_KIND_DATASET: return "dataset";
        case VOBENCH_KIND_ODOMETRY: return "odometry";
        case VOBENCH_KIND_FILTER: return "filter";
        default: return "unknown";
    }
}

std::string validate_descriptor(const vobench_plugin_descriptor* d) {
    if (d == nullptr) return "the entry function returned no descriptor (NULL) for ABI 1";
    if (d->struct_size < kMinDescriptorSize)
        return "descriptor struct_size " + std::to_string(d->struct_size) + " is smaller than the ABI 1 minimum " +
               std::to_string(kMinDescriptorSize);
    if (d->abi_version != VOBENCH_ABI_VERSION)
        return "descriptor says ABI " + std::to_string(d->abi_version) + ", this host speaks ABI " + std::to_string(VOBENCH_ABI_VERSION);
    if (d->api_version < 1) return "descriptor says API version 0";
    if (!is_identifier(d->name)) return "descriptor name is missing or not an identifier [a-z0-9_]+";
    if (d->version == nullptr || *d->version == '\0') return "descriptor has no version";
    if (d->description == nullptr) return "descriptor has no description";
    if (d->license == nullptr || *d->license == '\0') return "descriptor has no license";
    if (std::string why = check_param_table(d->param_count, d->params); !why.empty()) return why;
    if (d->kind == VOBENCH_KIND_DATASET) {
        const vobench_dataset_api* t = d->dataset;
        if (t == nullptr) return "dataset plugin without a dataset table";
        if (d->odometry != nullptr) return "dataset plugin also fills the odometry table";
        if (t->struct_size < kMinDatasetApiSize)
            return "dataset table struct_size " + std::to_string(t->struct_size) + " is smaller than " + std::to_string(kMinDatasetApiSize);
        if (!t->create || !t->open || !t->describe || !t->read_frame || !t->last_error || !t->destroy)
            return "dataset table has a NULL function";
    } else if (d->kind == VOBENCH_KIND_ODOMETRY) {
        const vobench_odometry_api* t = d->odometry;
        if (t == nullptr) return "odometry plugin without an odometry table";
        if (d->dataset != nullptr) return "odometry plugin also fills the dataset table";
        if (t->struct_size < kMinOdometryApiSize)
            return "odometry table struct_size " + std::to_string(t->struct_size) + " is smaller than " +
                   std::to_string(kMinOdometryApiSize);
        if (!t->create || !t->start || !t->process || !t->last_error || !t->destroy)
            return "odometry table has a NULL function (only reset may be NULL)";
    } else if (d->kind == VOBENCH_KIND_FILTER) {
        if (!VOBENCH_HAS_FIELD(d, vobench_plugin_descriptor, filter) || d->filter == nullptr)
            return "filter plugin without a filter table (descriptor of API 3 or later needed)";
        if (d->dataset != nullptr || d->odometry != nullptr) return "filter plugin also fills the dataset or odometry table";
        const vobench_filter_api* t = d->filter;
        if (t->struct_size < kMinFilterApiSize)
            return "filter table struct_size " + std::to_string(t->struct_size) + " is smaller than " + std::to_string(kMinFilterApiSize);
        if (!t->create || !t->start || !t->apply || !t->last_error || !t->destroy) return "filter table has a NULL function";
    } else {
        return "unknown plugin kind " + std::to_string(d->kind);
    }
    return "";
}

std::shared_ptr<const PluginLibrary> PluginLibrary::load(const std::filesystem::path& path) {
    const std::string where = path.string() + ": ";
    std::error_code fs_error;
    if (!std::filesystem::is_regular_file(path, fs_error)) throw PluginLoadError(where + "no such file");

    std::shared_ptr<PluginLibrary> plugin(new PluginLibrary());
    plugin->path_ = path;
    boost::system::error_code ec;
    // rtld_local: two plugins may carry symbols of the same name without clashing.
    plugin->library_.load(boost::dll::fs::path(path.string()), boost::dll::load_mode::rtld_lazy | boost::dll::load_mode::rtld_local, ec);
    if (ec) throw PluginLoadError(where + "cannot be loaded as a shared library (" + ec.message() + ")");

    if (!plugin->library_.has(VOBENCH_ENTRY_SYMBOL)) {
        // Name another generation's entry if the library has one, so the user knows what to rebuild.
        for (int abi = 0; abi < 10; ++abi) {
            const std::string other = "vobench_plugin_entry_v" + std::to_string(abi);
            if (abi != static_cast<int>(VOBENCH_ABI_VERSION) && plugin->library_.has(other))
                throw PluginLoadError(where + "built for plugin ABI " + std::to_string(abi) + " (exports " + other +
                                      "), this host speaks ABI " + std::to_string(VOBENCH_ABI_VERSION));
        }
        throw PluginLoadError(where + "not a vobench plugin (no " VOBENCH_ENTRY_SYMBOL " symbol)");
    }
    plugin->entry_ = plugin->library_.get<const vobench_plugin_descriptor*(uint32_t, uint32_t)>(VOBENCH_ENTRY_SYMBOL);
    plugin->descriptor_ = plugin->entry_(VOBENCH_ABI_VERSION, VOBENCH_API_VERSION);
    if (std::string why = validate_descriptor(plugin->descriptor_); !why.empty()) throw PluginLoadError(where + why);

    const vobench_plugin_descriptor& d = *plugin->descriptor_;
    PluginInfo& info = plugin->info_;
    info.path = path;
    info.name = d.name;
    info.version = clean_text(d.version);
    info.description = clean_text(d.description, true);
    info.license = clean_text(d.license);
    info.url = d.url ? clean_text(d.url) : "";
    info.kind = d.kind;
    info.abi_version = d.abi_version;
    info.api_version = d.api_version;
    info.params = params_of_table(d.param_count, d.params);
    info.table_size = info.params.size();
    if (d.kind == VOBENCH_KIND_DATASET)
        info.has_extra_params = VOBENCH_HAS_FIELD(d.dataset, vobench_dataset_api, extra_params) && d.dataset->extra_params != nullptr;
    else if (d.kind == VOBENCH_KIND_ODOMETRY)
        info.has_extra_params = VOBENCH_HAS_FIELD(d.odometry, vobench_odometry_api, extra_params) && d.odometry->extra_params != nullptr;
    return plugin;
}

}  // namespace vobench
