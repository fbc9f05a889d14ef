#include "abi/instances.hpp"

#include <vobench/plugin.hpp>

namespace vobench {

const char* status_name(vobench_status status) {
    switch (status) {
    case VOBENCH_OK: return "ok";
    case VOBENCH_ERROR: return "error";
    case VOBENCH_INVALID_ARGUMENT: return "invalid argument";
    case VOBENCH_IO_ERROR: return "I/O error";
    case VOBENCH_OUT_OF_RANGE: return "out of range";
    case VOBENCH_UNSUPPORTED: return "unsupported";
    case VOBENCH_CANCELLED: return "cancelled";
    case VOBENCH_NO_MEMORY: return "out of memory";
    default: return "unknown status";
    }
}

void validate_params(const PluginLibrary& plugin, const ParamMap& params) {
    for (const auto& [key, value] : params) {
        const sdk::Param* found = nullptr;
        for (const sdk::Param& p : plugin.params())
            if (p.name == key) found = &p;
        if (found == nullptr) {
            std::string known;
            for (const sdk::Param& p : plugin.params()) known += (known.empty() ? "" : ", ") + p.name;
            throw std::invalid_argument("plugin '" + plugin.name() + "' has no parameter '" + key + "' (it has: " +
                                        (known.empty() ? "none" : known) + ")");
        }
        const std::string why = sdk::check_param_value(*found, value);
        if (!why.empty())
            throw std::invalid_argument("plugin '" + plugin.name() + "', parameter '" + key + "': " + why);
    }
}

ParamView::ParamView(const ParamMap& params) {
    for (const auto& [k, v] : params) {
        keys_.push_back(k);
        values_.push_back(v);
    }
    for (std::size_t i = 0; i < keys_.size(); ++i) {
        key_ptrs_.push_back(keys_[i].c_str());
        value_ptrs_.push_back(values_[i].c_str());
    }
    view_.struct_size = sizeof(vobench_params);
    view_.count = static_cast<uint32_t>(keys_.size());
    view_.keys = key_ptrs_.data();
    view_.values = value_ptrs_.data();
}

// ----- datasets ----------------------------------------------------------------------------------

DatasetInstance::DatasetInstance(PluginPtr plugin)
    : plugin_(std::move(plugin)), api_(plugin_->descriptor().dataset), host_(std::make_unique<HostContext>(plugin_->name())) {
    handle_ = api_->create(host_->services());
    if (handle_ == nullptr) throw PluginCallError("plugin '" + plugin_->name() + "': create() returned NULL", VOBENCH_NO_MEMORY);
}

DatasetInstance::~DatasetInstance() { api_->destroy(handle_); }

void DatasetInstance::fail(const char* call, vobench_status status) const {
    const char* message = api_->last_error(handle_);
    throw PluginCallError("plugin '" + plugin_->name() + "': " + call + " failed (" + status_name(status) +
                              "): " + (message && *message ? message : "no message"),
                          status);
}

void DatasetInstance::open(const std::string& path, const ParamMap& options) {
    validate_params(*plugin_, options);
    const ParamView view(options);
    if (vobench_status s = api_->open(handle_, path.c_str(), view.get()); s != VOBENCH_OK) fail("open", s);
    if (vobench_status s = api_->describe(handle_, &info_); s != VOBENCH_OK) fail("describe", s);
    if (info_ == nullptr || info_->camera == nullptr)
        throw PluginCallError("plugin '" + plugin_->name() + "': describe() gave no sequence info or camera", VOBENCH_ERROR);
}

const vobench_frame& DatasetInstance::read(uint64_t index) {
    const vobench_frame* frame = nullptr;
    if (vobench_status s = api_->read_frame(handle_, index, &frame); s != VOBENCH_OK) fail("read_frame", s);
    if (frame == nullptr || frame->color == nullptr || frame->depth == nullptr)
        throw PluginCallError("plugin '" + plugin_->name() + "': read_frame(" + std::to_string(index) +
                                  ") returned an incomplete frame",
                              VOBENCH_ERROR);
    return *frame;
}

// ----- odometry ----------------------------------------------------------------------------------

OdometryInstance::OdometryInstance(PluginPtr plugin)
    : plugin_(std::move(plugin)), api_(plugin_->descriptor().odometry), host_(std::make_unique<HostContext>(plugin_->name())) {
    handle_ = api_->create(host_->services());
    if (handle_ == nullptr) throw PluginCallError("plugin '" + plugin_->name() + "': create() returned NULL", VOBENCH_NO_MEMORY);
}

OdometryInstance::~OdometryInstance() { api_->destroy(handle_); }

std::string OdometryInstance::last_error() const {
    const char* message = api_->last_error(handle_);
    return message && *message ? message : "no message";
}

void OdometryInstance::start(const vobench_camera& camera, const ParamMap& params, uint64_t seed) {
    validate_params(*plugin_, params);
    const ParamView view(params);
    vobench_odometry_config config{};
    config.struct_size = sizeof(config);
    config.camera = &camera;
    config.params = view.get();
    config.seed = seed;
    if (vobench_status s = api_->start(handle_, &config); s != VOBENCH_OK)
        throw PluginCallError("plugin '" + plugin_->name() + "': start failed (" + status_name(s) + "): " + last_error(), s);
}

void OdometryInstance::reset() {
    if (api_->reset == nullptr) throw PluginCallError("plugin '" + plugin_->name() + "' cannot reset", VOBENCH_UNSUPPORTED);
    if (vobench_status s = api_->reset(handle_); s != VOBENCH_OK)
        throw PluginCallError("plugin '" + plugin_->name() + "': reset failed (" + status_name(s) + "): " + last_error(), s);
}

}  // namespace vobench
