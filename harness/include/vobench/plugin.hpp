// plugin.hpp — the optional C++ SDK over vobench_plugin.h.
//
// A plugin author writes one class and one macro:
//
//     class MyVo : public vobench::sdk::Odometry {
//     public:
//         static vobench::sdk::PluginInfo info();          // name, version, parameter table ...
//         void start(const vobench_camera&, const vobench::sdk::Params&, uint64_t seed) override;
//         vobench_tracking_status process(const vobench_frame&, vobench_pose&) override;
//     };
//     VOBENCH_ODOMETRY_PLUGIN(MyVo)
//
// (VOBENCH_DATASET_PLUGIN likewise for a vobench::sdk::Dataset.) The macro defines the C entry symbol,
// builds the static descriptor from info() once, and wraps every call so that no exception crosses the
// C boundary: vobench::sdk::Error carries its status, std::bad_alloc becomes VOBENCH_NO_MEMORY, any
// other exception VOBENCH_ERROR, each with its message in last_error().
//
// Header-only, C++17, no dependency beyond the standard library: plugins never link the harness.
#ifndef VOBENCH_PLUGIN_HPP
#define VOBENCH_PLUGIN_HPP

#include <vobench/vobench_plugin.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vobench::sdk {

// ----- errors ------------------------------------------------------------------------------------

// Throw this from plugin code to return a specific status with a message.
class Error : public std::runtime_error {
public:
    Error(vobench_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
    vobench_status status() const noexcept { return status_; }

private:
    vobench_status status_;
};

// ----- parameter parsing (shared with the host, which validates configs with the same rules) -------

// Each returns false when `text` is not a complete, valid value of the type.
inline bool parse_bool(const std::string& text, bool& out) {
    if (text == "true" || text == "1" || text == "on" || text == "yes") {
        out = true;
        return true;
    }
    if (text == "false" || text == "0" || text == "off" || text == "no") {
        out = false;
        return true;
    }
    return false;
}

inline bool parse_int(const std::string& text, long long& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtoll(text.c_str(), &end, 10);
    return errno == 0 && end == text.c_str() + text.size();
}

inline bool parse_double(const std::string& text, double& out) {
    if (text.empty()) return false;
    char* end = nullptr;
    errno = 0;
    out = std::strtod(text.c_str(), &end);
    return errno == 0 && end == text.c_str() + text.size() && std::isfinite(out);
}

// True when `word` is one of the '|'-separated `choices`.
inline bool is_choice(const std::string& word, const std::string& choices) {
    std::size_t begin = 0;
    while (begin <= choices.size()) {
        std::size_t end = choices.find('|', begin);
        if (end == std::string::npos) end = choices.size();
        if (choices.compare(begin, end - begin, word) == 0 && end - begin == word.size()) return true;
        begin = end + 1;
    }
    return false;
}

// One parameter of the table a plugin publishes.
struct Param {
    std::string name;
    vobench_param_type type = VOBENCH_PARAM_STRING;
    std::string default_value;
    double min_value = 0.0;
    double max_value = 0.0;
    std::string choices;  // ENUM only: "a|b|c"
    std::string help;
};

// Checks `text` against one parameter's type and range; returns an empty string when valid, or the
// reason it is not.
inline std::string check_param_value(const Param& p, const std::string& text) {
    switch (p.type) {
        case VOBENCH_PARAM_BOOL: {
            bool b;
            return parse_bool(text, b) ? "" : "'" + text + "' is not a boolean (true/false)";
        }
        case VOBENCH_PARAM_INT: {
            long long v;
            if (!parse_int(text, v)) return "'" + text + "' is not an integer";
            if (double(v) < p.min_value || double(v) > p.max_value)
                return "'" + text + "' is outside [" + std::to_string((long long)p.min_value) + ", " +
                       std::to_string((long long)p.max_value) + "]";
            return "";
        }
        case VOBENCH_PARAM_DOUBLE: {
            double v;
            if (!parse_double(text, v)) return "'" + text + "' is not a finite number";
            if (v < p.min_value || v > p.max_value)
                return "'" + text + "' is outside [" + std::to_string(p.min_value) + ", " + std::to_string(p.max_value) + "]";
            return "";
        }
        case VOBENCH_PARAM_ENUM: return is_choice(text, p.choices) ? "" : "'" + text + "' is not one of " + p.choices;
        case VOBENCH_PARAM_STRING: return "";
        default: return "unknown parameter type";
    }
}

// What info() returns: the static description of a plugin.
struct PluginInfo {
    std::string name;
    std::string version;
    std::string description;
    std::string license;
    std::string url;
    std::vector<Param> params;
    // API 3: instances declare more parameters, by the values of some of these (Odometry::extra_params).
    bool has_extra_params = false;
};

// Parameter values as given, completed with the table's defaults. Getters throw Error on a name that
// is not in the table or a value of the wrong type, so a plugin's own mistakes surface as messages.
class Params {
public:
    Params() = default;
    Params(const std::vector<Param>& table, const vobench_params* given) : table_(table) {
        for (const Param& p : table) values_[p.name] = p.default_value;
        if (given == nullptr) return;
        for (uint32_t i = 0; i < given->count; ++i) {
            const std::string key = given->keys[i] ? given->keys[i] : "";
            const std::string value = given->values[i] ? given->values[i] : "";
            const Param* p = find(key);
            if (p == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "unknown parameter '" + key + "'");
            const std::string why = check_param_value(*p, value);
            if (!why.empty()) throw Error(VOBENCH_INVALID_ARGUMENT, "parameter '" + key + "': " + why);
            values_[key] = value;
            given_.insert(key);
        }
    }

    // Whether `name` was given rather than taken from the table's default.
    bool given(const std::string& name) const { return given_.count(name) > 0; }

    // A copy in which each parameter not given takes its value from `defaults` where that names it,
    // instead of from the table: a plugin's profiles, sets of defaults that an explicitly given
    // parameter still overrides. Values are checked as given ones are; a name not in the table, or a
    // value it refuses, is the plugin's own error.
    Params with_defaults(const std::map<std::string, std::string>& defaults) const {
        Params out = *this;
        for (const auto& [name, value] : defaults) {
            const Param* p = find(name);
            if (p == nullptr) throw Error(VOBENCH_ERROR, "plugin's defaults name undeclared parameter '" + name + "'");
            const std::string why = check_param_value(*p, value);
            if (!why.empty()) throw Error(VOBENCH_ERROR, "plugin's default for '" + name + "': " + why);
            if (!given(name)) out.values_[name] = value;
        }
        return out;
    }

    const std::string& get_string(const std::string& name) const {
        auto it = values_.find(name);
        if (it == values_.end()) throw Error(VOBENCH_ERROR, "plugin asked for undeclared parameter '" + name + "'");
        return it->second;
    }
    long long get_int(const std::string& name) const {
        long long v;
        if (!parse_int(get_string(name), v)) throw Error(VOBENCH_INVALID_ARGUMENT, "parameter '" + name + "' is not an integer");
        return v;
    }
    double get_double(const std::string& name) const {
        double v;
        if (!parse_double(get_string(name), v)) throw Error(VOBENCH_INVALID_ARGUMENT, "parameter '" + name + "' is not a number");
        return v;
    }
    bool get_bool(const std::string& name) const {
        bool v;
        if (!parse_bool(get_string(name), v)) throw Error(VOBENCH_INVALID_ARGUMENT, "parameter '" + name + "' is not a boolean");
        return v;
    }
    const std::map<std::string, std::string>& all() const { return values_; }

private:
    const Param* find(const std::string& name) const {
        for (const Param& p : table_)
            if (p.name == name) return &p;
        return nullptr;
    }
    std::vector<Param> table_;
    std::map<std::string, std::string> values_;
    std::set<std::string> given_;
};

// ----- host services -----------------------------------------------------------------------------

class Host {
public:
    explicit Host(const vobench_host_services* services) : services_(services) {}

    void log(vobench_log_level level, const std::string& message) const {
        if (has(&vobench_host_services::log)) services_->log(services_->context, level, message.c_str());
    }
    void info(const std::string& message) const { log(VOBENCH_LOG_INFO, message); }
    void warn(const std::string& message) const { log(VOBENCH_LOG_WARNING, message); }
    void stage_begin(const char* stage) const {
        if (has(&vobench_host_services::stage_begin)) services_->stage_begin(services_->context, stage);
    }
    void stage_end(const char* stage) const {
        if (has(&vobench_host_services::stage_end)) services_->stage_end(services_->context, stage);
    }
    void counter(const char* name, double value) const {
        if (has(&vobench_host_services::counter)) services_->counter(services_->context, name, value);
    }
    bool cancelled() const { return has(&vobench_host_services::is_cancelled) && services_->is_cancelled(services_->context) != 0; }

    // Times a stage for the lifetime of the object: { Host::Stage s(host(), "detection"); ... }
    class Stage {
    public:
        Stage(const Host& host, const char* name) : host_(host), name_(name) { host_.stage_begin(name_); }
        ~Stage() { host_.stage_end(name_); }
        Stage(const Stage&) = delete;
        Stage& operator=(const Stage&) = delete;

    private:
        const Host& host_;
        const char* name_;
    };

private:
    // A function is usable when the host's struct covers it and set it.
    template <typename F>
    bool has(F vobench_host_services::*member) const {
        if (services_ == nullptr) return false;
        const std::size_t offset = reinterpret_cast<std::size_t>(&(reinterpret_cast<const vobench_host_services*>(0)->*member));
        return services_->struct_size >= offset + sizeof(F) && services_->*member != nullptr;
    }
    const vobench_host_services* services_;
};

// ----- the classes plugin authors derive from ----------------------------------------------------

// The host services of an instance, for every kind: set by the SDK before the first call.
class WithHost {
public:
    const Host& host() const { return *host_; }
    void attach_host(const Host* host) { host_ = host; }

private:
    const Host* host_ = nullptr;
};

class Odometry : public WithHost {
public:
    virtual ~Odometry() = default;
    // Called once before the first frame. `camera` is the colour camera of the frames to come.
    virtual void start(const vobench_camera& camera, const Params& params, uint64_t seed) = 0;
    // Fill `pose` (camera-to-world) for this frame and return the tracking status. Throw on error.
    virtual vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) = 0;
    // Forget the state (default: not supported).
    virtual void reset() { throw Error(VOBENCH_UNSUPPORTED, "this plugin cannot reset"); }
    // Only when info().has_extra_params: the parameters this instance takes beyond info()'s table, given
    // the values of that table's own (`given`, completed with defaults). Called at most once, before start().
    virtual std::vector<Param> extra_params(const Params& given) {
        (void)given;
        return {};
    }
};

class Dataset : public WithHost {
public:
    virtual ~Dataset() = default;
    virtual void open(const std::string& path, const Params& options) = 0;
    // The returned reference must stay valid until destruction.
    virtual const vobench_sequence_info& describe() = 0;
    // The returned frame must stay valid until the next read_frame() or destruction.
    virtual const vobench_frame& read_frame(uint64_t index) = 0;
    // As Odometry::extra_params, called before open().
    virtual std::vector<Param> extra_params(const Params& given) {
        (void)given;
        return {};
    }
};

// A filter (API 3): perturbs each frame between the reader and the odometry plugin.
class Filter : public WithHost {
public:
    virtual ~Filter() = default;
    // Called once before the first frame; `camera` is the frames' camera.
    virtual void start(const vobench_camera& camera, const Params& params, uint64_t seed) = 0;
    // The perturbed frame (the filter's own, valid until the next apply() or destruction), or nullptr
    // to drop this frame (the plugin does not see it). Throw on error.
    virtual const vobench_frame* apply(const vobench_frame& frame) = 0;
    // After start(): the camera of the frames apply() gives (default: the input camera unchanged).
    virtual vobench_camera output_camera(const vobench_camera& input) const { return input; }
};

// A frame a filter owns: a deep copy of one it was given (rows packed), whose pixels it may change.
class FrameBuffer {
public:
    void copy_from(const vobench_frame& in) {
        frame_ = in;
        frame_.struct_size = sizeof(vobench_frame);
        copy_image(*in.color, color_bytes_, color_);
        copy_image(*in.depth, depth_bytes_, depth_);
        frame_.color = &color_;
        frame_.depth = &depth_;
    }
    const vobench_frame& frame() const { return frame_; }
    vobench_frame& frame() { return frame_; }
    // Rows of width * bytes-per-pixel, no padding.
    uint8_t* color() { return color_bytes_.data(); }
    uint8_t* depth() { return depth_bytes_.data(); }
    const vobench_image& color_image() const { return color_; }
    const vobench_image& depth_image() const { return depth_; }

private:
    static int bytes_per_pixel(vobench_pixel_format f) {
        return f == VOBENCH_PIXEL_GRAY8 ? 1 : f == VOBENCH_PIXEL_DEPTH_U16 ? 2 : f == VOBENCH_PIXEL_DEPTH_F32 ? 4 : 3;
    }
    static void copy_image(const vobench_image& in, std::vector<uint8_t>& bytes, vobench_image& out) {
        const std::size_t row = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(bytes_per_pixel(in.format));
        bytes.resize(row * static_cast<std::size_t>(in.height));
        for (int y = 0; y < in.height; ++y)
            std::memcpy(bytes.data() + row * static_cast<std::size_t>(y),
                        static_cast<const uint8_t*>(in.data) + static_cast<std::ptrdiff_t>(y) * in.stride_bytes, row);
        out = in;
        out.struct_size = sizeof(vobench_image);
        out.stride_bytes = static_cast<int32_t>(row);
        out.data = bytes.data();
    }
    std::vector<uint8_t> color_bytes_, depth_bytes_;
    vobench_image color_{}, depth_{};
    vobench_frame frame_{};
};

namespace detail {

// Runs `body`, turning any exception into a status and a stored message.
template <typename Body>
vobench_status guarded(std::string& error, Body&& body) noexcept {
    try {
        error.clear();
        body();
        return VOBENCH_OK;
    } catch (const Error& e) {
        error = e.what();
        return e.status();
    } catch (const std::bad_alloc&) {
        error = "out of memory";
        return VOBENCH_NO_MEMORY;
    } catch (const std::exception& e) {
        error = e.what();
        return VOBENCH_ERROR;
    } catch (...) {
        error = "unknown exception";
        return VOBENCH_ERROR;
    }
}

// The C rows of a parameter table; they point into `table`, which must outlive them.
inline std::vector<vobench_param_desc> param_descs(const std::vector<Param>& table) {
    std::vector<vobench_param_desc> out;
    for (const Param& p : table) {
        vobench_param_desc d{};
        d.struct_size = sizeof(vobench_param_desc);
        d.name = p.name.c_str();
        d.type = p.type;
        d.default_value = p.default_value.c_str();
        d.min_value = p.min_value;
        d.max_value = p.max_value;
        d.choices = p.choices.empty() ? nullptr : p.choices.c_str();
        d.help = p.help.c_str();
        out.push_back(d);
    }
    return out;
}

// Owns the strings and tables a descriptor points to; built once per plugin class.
struct DescriptorStore {
    PluginInfo info;
    std::vector<vobench_param_desc> params;
    vobench_plugin_descriptor descriptor{};

    DescriptorStore(PluginInfo i, vobench_plugin_kind kind) : info(std::move(i)) {
        params = param_descs(info.params);
        descriptor.struct_size = sizeof(vobench_plugin_descriptor);
        descriptor.abi_version = VOBENCH_ABI_VERSION;
        descriptor.api_version = VOBENCH_API_VERSION;
        descriptor.kind = kind;
        descriptor.name = info.name.c_str();
        descriptor.version = info.version.c_str();
        descriptor.description = info.description.c_str();
        descriptor.license = info.license.c_str();
        descriptor.url = info.url.empty() ? nullptr : info.url.c_str();
        descriptor.param_count = static_cast<uint32_t>(params.size());
        descriptor.params = params.empty() ? nullptr : params.data();
    }
};

template <typename T>
struct Instance {
    explicit Instance(const vobench_host_services* services) : host(services) {}
    Host host;
    std::unique_ptr<T> impl;
    std::string error;
    // API 3: what impl->extra_params() answered (asked once), and its C rows.
    bool asked = false;
    std::vector<Param> extra;
    std::vector<vobench_param_desc> extra_descs;
};

// What both bridges share: the instance handle, creation, the error message, destruction, and the
// static descriptor built once from Impl::info().
template <typename Impl, typename Handle, vobench_plugin_kind Kind>
struct BridgeBase {
    using Self = Instance<Impl>;
    static Self* self(Handle* h) { return reinterpret_cast<Self*>(h); }

    static Handle* create(const vobench_host_services* host) noexcept {
        try {
            auto* s = new Self(host);
            s->impl = std::make_unique<Impl>();
            s->impl->attach_host(&s->host);
            return reinterpret_cast<Handle*>(s);
        } catch (...) {
            return nullptr;
        }
    }
    static const char* last_error(Handle* h) noexcept { return self(h)->error.c_str(); }

    // Asks impl->extra_params once, with the values of info()'s own parameters among `given`.
    static void ask_extra(Self* s, const vobench_params* given) {
        if (s->asked || !store().info.has_extra_params) return;
        std::vector<const char*> keys, values;
        for (uint32_t i = 0; given != nullptr && i < given->count; ++i)
            for (const Param& p : store().info.params)
                if (given->keys[i] != nullptr && p.name == given->keys[i]) {
                    keys.push_back(given->keys[i]);
                    values.push_back(given->values[i]);
                }
        const vobench_params own{sizeof(vobench_params), static_cast<uint32_t>(keys.size()), keys.data(), values.data()};
        s->extra = s->impl->extra_params(Params(store().info.params, &own));
        s->extra_descs = param_descs(s->extra);
        s->asked = true;
    }
    static vobench_status extra_params(Handle* h, const vobench_params* given, uint32_t* count, const vobench_param_desc** out) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (count == nullptr || out == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "extra_params() needs output pointers");
            ask_extra(s, given);
            *count = static_cast<uint32_t>(s->extra_descs.size());
            *out = s->extra_descs.empty() ? nullptr : s->extra_descs.data();
        });
    }
    // The table start()/open() validate against: info()'s and the instance's extra parameters.
    static Params params_of(Self* s, const vobench_params* given) {
        ask_extra(s, given);
        std::vector<Param> table = store().info.params;
        table.insert(table.end(), s->extra.begin(), s->extra.end());
        return Params(table, given);
    }
    static void destroy(Handle* h) noexcept { delete self(h); }

    // info() is plugin code and may throw: then the entry answers NULL (entry_with), and this false.
    static bool has_extra() noexcept {
        try {
            return store().info.has_extra_params;
        } catch (...) {
            return false;
        }
    }
    static const DescriptorStore& store() {
        static const DescriptorStore s(Impl::info(), Kind);
        return s;
    }
    // The descriptor with `table` in its kind's slot; NULL for another ABI, or when info() (plugin
    // code) throws — no exception escapes the entry either.
    template <typename Table>
    static const vobench_plugin_descriptor* entry_with(uint32_t abi, uint32_t api, const Table* table,
                                                       const Table* vobench_plugin_descriptor::*slot) noexcept {
        if (abi != VOBENCH_ABI_VERSION || api < 1) return nullptr;
        try {
            static const vobench_plugin_descriptor descriptor = [&] {
                vobench_plugin_descriptor d = store().descriptor;
                d.*slot = table;
                return d;
            }();
            return &descriptor;
        } catch (...) {
            return nullptr;
        }
    }
};

template <typename Impl>
struct OdometryBridge : BridgeBase<Impl, vobench_odometry, VOBENCH_KIND_ODOMETRY> {
    using Base = BridgeBase<Impl, vobench_odometry, VOBENCH_KIND_ODOMETRY>;
    using Base::self;

    static vobench_status start(vobench_odometry* h, const vobench_odometry_config* config) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (config == nullptr || config->camera == nullptr)
                throw Error(VOBENCH_INVALID_ARGUMENT, "start() needs a configuration with a camera");
            s->impl->start(*config->camera, Base::params_of(s, config->params), config->seed);
        });
    }
    static vobench_status process(vobench_odometry* h, const vobench_frame* frame, vobench_pose* pose,
                                  vobench_tracking_status* status) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (frame == nullptr || pose == nullptr || status == nullptr)
                throw Error(VOBENCH_INVALID_ARGUMENT, "process() needs a frame, a pose and a status");
            vobench_pose out{};
            out.struct_size = sizeof(vobench_pose);
            out.timestamp = frame->timestamp;
            out.qw = 1.0;
            *status = s->impl->process(*frame, out);
            // Write back only what the host's struct covers.
            const uint32_t size = pose->struct_size < sizeof(out) ? pose->struct_size : uint32_t(sizeof(out));
            const uint32_t host_size = pose->struct_size;
            std::memcpy(static_cast<void*>(pose), &out, size);
            pose->struct_size = host_size;
        });
    }
    static vobench_status reset(vobench_odometry* h) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] { s->impl->reset(); });
    }
    static const vobench_plugin_descriptor* entry(uint32_t abi, uint32_t api) noexcept {
        static const vobench_odometry_api table = {sizeof(vobench_odometry_api),
                                                   &Base::create,
                                                   &start,
                                                   &process,
                                                   &reset,
                                                   &Base::last_error,
                                                   &Base::destroy,
                                                   Base::has_extra() ? &Base::extra_params : nullptr};
        return Base::entry_with(abi, api, &table, &vobench_plugin_descriptor::odometry);
    }
};

template <typename Impl>
struct DatasetBridge : BridgeBase<Impl, vobench_dataset, VOBENCH_KIND_DATASET> {
    using Base = BridgeBase<Impl, vobench_dataset, VOBENCH_KIND_DATASET>;
    using Base::self;

    static vobench_status open(vobench_dataset* h, const char* path, const vobench_params* options) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (path == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "open() needs a path");
            s->impl->open(path, Base::params_of(s, options));
        });
    }
    static vobench_status describe(vobench_dataset* h, const vobench_sequence_info** out) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (out == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "describe() needs an output pointer");
            *out = &s->impl->describe();
        });
    }
    static vobench_status read_frame(vobench_dataset* h, uint64_t index, const vobench_frame** out) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (out == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "read_frame() needs an output pointer");
            *out = &s->impl->read_frame(index);
        });
    }
    static const vobench_plugin_descriptor* entry(uint32_t abi, uint32_t api) noexcept {
        static const vobench_dataset_api table = {sizeof(vobench_dataset_api),
                                                  &Base::create,
                                                  &open,
                                                  &describe,
                                                  &read_frame,
                                                  &Base::last_error,
                                                  &Base::destroy,
                                                  Base::has_extra() ? &Base::extra_params : nullptr};
        return Base::entry_with(abi, api, &table, &vobench_plugin_descriptor::dataset);
    }
};

template <typename Impl>
struct FilterBridge : BridgeBase<Impl, vobench_filter, VOBENCH_KIND_FILTER> {
    using Base = BridgeBase<Impl, vobench_filter, VOBENCH_KIND_FILTER>;
    using Base::self;

    static vobench_status start(vobench_filter* h, const vobench_filter_config* config) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (config == nullptr || config->camera == nullptr)
                throw Error(VOBENCH_INVALID_ARGUMENT, "start() needs a configuration with a camera");
            s->impl->start(*config->camera, Params(Base::store().info.params, config->params), config->seed);
            if (VOBENCH_HAS_FIELD(config, vobench_filter_config, output_camera) && config->output_camera != nullptr) {
                const uint32_t size = config->output_camera->struct_size;
                *config->output_camera = s->impl->output_camera(*config->camera);
                config->output_camera->struct_size = size;
            }
        });
    }
    static vobench_status apply(vobench_filter* h, const vobench_frame* in, const vobench_frame** out) noexcept {
        auto* s = self(h);
        return guarded(s->error, [&] {
            if (in == nullptr || out == nullptr) throw Error(VOBENCH_INVALID_ARGUMENT, "apply() needs a frame and an output pointer");
            *out = s->impl->apply(*in);
        });
    }
    static const vobench_plugin_descriptor* entry(uint32_t abi, uint32_t api) noexcept {
        if (api < 3) return nullptr;  // a filter needs a host that knows filters
        static const vobench_filter_api table = {sizeof(vobench_filter_api), &Base::create, &start, &apply,
                                                 &Base::last_error,          &Base::destroy};
        return Base::entry_with(abi, api, &table, &vobench_plugin_descriptor::filter);
    }
};

}  // namespace detail
}  // namespace vobench::sdk

// Defines the plugin's entry symbol for an Odometry (resp. Dataset) subclass with a static info().
#define VOBENCH_ODOMETRY_PLUGIN(Class)                                                                              \
    extern "C" VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t host_abi_version,   \
                                                                                       uint32_t host_api_version) { \
        return ::vobench::sdk::detail::OdometryBridge<Class>::entry(host_abi_version, host_api_version);            \
    }

#define VOBENCH_DATASET_PLUGIN(Class)                                                                               \
    extern "C" VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t host_abi_version,   \
                                                                                       uint32_t host_api_version) { \
        return ::vobench::sdk::detail::DatasetBridge<Class>::entry(host_abi_version, host_api_version);             \
    }

#define VOBENCH_FILTER_PLUGIN(Class)                                                                                \
    extern "C" VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t host_abi_version,   \
                                                                                       uint32_t host_api_version) { \
        return ::vobench::sdk::detail::FilterBridge<Class>::entry(host_abi_version, host_api_version);              \
    }

#endif  // VOBENCH_PLUGIN_HPP
