#include "abi/instances.hpp"

#include <vobench/plugin.hpp>

#include <cmath>

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

void validate_params(const PluginInfo& plugin, const ParamMap& params) {
    for (const auto& [key, value] : params) {
        const sdk::Param* found = nullptr;
        for (const sdk::Param& p : plugin.params)
            if (p.name == key) found = &p;
        if (found == nullptr) {
            std::string known;
            for (const sdk::Param& p : plugin.params) known += (known.empty() ? "" : ", ") + p.name;
            throw std::invalid_argument("plugin '" + plugin.name + "' has no parameter '" + key +
                                        "' (it has: " + (known.empty() ? "none" : known) + ")");
        }
        const std::string why = sdk::check_param_value(*found, value);
        if (!why.empty()) throw std::invalid_argument("plugin '" + plugin.name + "', parameter '" + key + "': " + why);
    }
}

ParamMap table_params(const PluginInfo& plugin, const ParamMap& params) {
    ParamMap given;
    for (std::size_t i = 0; i < plugin.table_size && i < plugin.params.size(); ++i)
        if (auto it = params.find(plugin.params[i].name); it != params.end()) given.insert(*it);
    return given;
}

namespace {

// The table of `library` extended by the instance's answer to extra_params (API 3), for both kinds.
template <typename Api, typename Handle>
PluginInfo extended_params(const PluginLibrary& library, const Api* api, Handle* handle, const ParamMap& params) {
    PluginInfo info = library.info();
    if (!info.has_extra_params) return info;
    const ParamMap given = table_params(info, params);
    validate_params(info, given);
    const ParamView view(given);
    uint32_t count = 0;
    const vobench_param_desc* table = nullptr;
    const std::string who = "plugin '" + info.name + "': ";
    if (vobench_status s = api->extra_params(handle, view.get(), &count, &table); s != VOBENCH_OK) {
        const char* message = api->last_error(handle);
        throw PluginCallError(who + "extra_params failed (" + status_name(s) + "): " + (message && *message ? message : "no message"), s);
    }
    std::vector<std::string> taken;
    for (const sdk::Param& p : info.params) taken.push_back(p.name);
    if (const std::string why = check_param_table(count, table, taken); !why.empty())
        throw PluginCallError(who + "extra_params gave a malformed table: " + why, VOBENCH_ERROR);
    for (sdk::Param& p : params_of_table(count, table)) info.params.push_back(std::move(p));
    return info;
}

}  // namespace

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

namespace {

int bytes_per_pixel(vobench_pixel_format f) {
    switch (f) {
        case VOBENCH_PIXEL_RGB8:
        case VOBENCH_PIXEL_BGR8: return 3;
        case VOBENCH_PIXEL_GRAY8: return 1;
        case VOBENCH_PIXEL_DEPTH_U16: return 2;
        case VOBENCH_PIXEL_DEPTH_F32: return 4;
        default: return 0;
    }
}

std::string image_problem(const vobench_image& im, const vobench_camera& camera, const char* what, bool depth) {
    const int bpp = bytes_per_pixel(im.format);
    const bool depth_format = im.format == VOBENCH_PIXEL_DEPTH_U16 || im.format == VOBENCH_PIXEL_DEPTH_F32;
    if (bpp == 0 || depth_format != depth) return std::string(what) + " has pixel format " + std::to_string(im.format);
    if (im.width != camera.width || im.height != camera.height)
        return std::string(what) + " is " + std::to_string(im.width) + "x" + std::to_string(im.height) + ", the camera " +
               std::to_string(camera.width) + "x" + std::to_string(camera.height);
    if (im.data == nullptr || im.stride_bytes < im.width * bpp)
        return std::string(what) + " has no data or a stride below width x pixel size";
    return "";
}

}  // namespace

std::string frame_problem(const vobench_frame& frame, const vobench_camera& camera) {
    if (std::string why = image_problem(*frame.color, camera, "colour image", false); !why.empty()) return why;
    if (std::string why = image_problem(*frame.depth, camera, "depth image", true); !why.empty()) return why;
    if (!(std::isfinite(frame.depth_scale) && frame.depth_scale > 0)) return "depth_scale is not a positive number";
    return "";
}

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

const PluginInfo& DatasetInstance::params_for(const ParamMap& options) {
    if (!params_) params_ = extended_params(*plugin_, api_, handle_, options);
    return *params_;
}

void DatasetInstance::open(const std::string& path, const ParamMap& options) {
    validate_params(params_for(options), options);
    const ParamView view(options);
    if (vobench_status s = api_->open(handle_, path.c_str(), view.get()); s != VOBENCH_OK) fail("open", s);
    if (vobench_status s = api_->describe(handle_, &info_); s != VOBENCH_OK) fail("describe", s);
    if (info_ == nullptr || info_->camera == nullptr)
        throw PluginCallError("plugin '" + plugin_->name() + "': describe() gave no sequence info or camera", VOBENCH_ERROR);
    const vobench_camera& c = *info_->camera;
    if (c.width <= 0 || c.height <= 0 || c.width > 16384 || c.height > 16384 || !(std::isfinite(c.fx) && c.fx > 0) ||
        !(std::isfinite(c.fy) && c.fy != 0) || !std::isfinite(c.cx) || !std::isfinite(c.cy))
        throw PluginCallError("plugin '" + plugin_->name() + "': describe() gave an unusable camera (" + std::to_string(c.width) + "x" +
                                  std::to_string(c.height) + ", fx " + std::to_string(c.fx) + ")",
                              VOBENCH_ERROR);
    if (info_->gt_count > 0 && info_->ground_truth == nullptr)
        throw PluginCallError("plugin '" + plugin_->name() + "': describe() declares ground truth but gives no array", VOBENCH_ERROR);
}

const vobench_frame& DatasetInstance::read(uint64_t index) {
    const vobench_frame* frame = nullptr;
    if (vobench_status s = api_->read_frame(handle_, index, &frame); s != VOBENCH_OK) fail("read_frame", s);
    if (frame == nullptr || frame->color == nullptr || frame->depth == nullptr)
        throw PluginCallError("plugin '" + plugin_->name() + "': read_frame(" + std::to_string(index) + ") returned an incomplete frame",
                              VOBENCH_ERROR);
    // An odometry plugin reads these images by their sizes and strides: a reader that lies about them
    // must fail here, named, not make the plugin read past a buffer and be blamed for the crash.
    const std::string why = frame_problem(*frame, *info_->camera);
    if (!why.empty())
        throw PluginCallError("plugin '" + plugin_->name() + "': read_frame(" + std::to_string(index) + ") returned a bad frame: " + why,
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

const PluginInfo& OdometryInstance::params_for(const ParamMap& params) {
    if (!params_) params_ = extended_params(*plugin_, api_, handle_, params);
    return *params_;
}

void OdometryInstance::start(const vobench_camera& camera, const ParamMap& params, uint64_t seed) {
    validate_params(params_for(params), params);
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

// ----- filters -----------------------------------------------------------------------------------

FilterInstance::FilterInstance(PluginPtr plugin)
    : plugin_(std::move(plugin)), api_(plugin_->descriptor().filter), host_(std::make_unique<HostContext>(plugin_->name())) {
    handle_ = api_->create(host_->services());
    if (handle_ == nullptr) throw PluginCallError("filter '" + plugin_->name() + "': create() returned NULL", VOBENCH_NO_MEMORY);
}

FilterInstance::~FilterInstance() { api_->destroy(handle_); }

void FilterInstance::start(const vobench_camera& camera, const ParamMap& params, uint64_t seed) {
    validate_params(plugin_->info(), params);
    const vobench_camera input = camera;
    camera_ = camera;
    const ParamView view(params);
    vobench_filter_config config{};
    config.struct_size = sizeof(config);
    config.camera = &input;
    config.params = view.get();
    config.seed = seed;
    config.output_camera = &camera_;  // preset to the input: a filter that keeps the geometry leaves it
    if (vobench_status s = api_->start(handle_, &config); s != VOBENCH_OK) {
        const char* message = api_->last_error(handle_);
        throw PluginCallError(
            "filter '" + plugin_->name() + "': start failed (" + status_name(s) + "): " + (message && *message ? message : "no message"),
            s);
    }
    camera_.struct_size = sizeof(camera_);
    const vobench_camera& c = camera_;
    if (c.width <= 0 || c.height <= 0 || c.width > 16384 || c.height > 16384 || !(std::isfinite(c.fx) && c.fx > 0) ||
        !(std::isfinite(c.fy) && c.fy != 0) || !std::isfinite(c.cx) || !std::isfinite(c.cy) || c.distortion_count < 0 ||
        c.distortion_count > 8)
        throw PluginCallError("filter '" + plugin_->name() + "': start() wrote an unusable output camera (" + std::to_string(c.width) +
                                  "x" + std::to_string(c.height) + ", fx " + std::to_string(c.fx) + ")",
                              VOBENCH_ERROR);
}

const vobench_frame* FilterInstance::apply(const vobench_frame& in) {
    const vobench_frame* out = nullptr;
    host_->begin_call();
    if (vobench_status s = api_->apply(handle_, &in, &out); s != VOBENCH_OK) {
        const char* message = api_->last_error(handle_);
        throw PluginCallError("filter '" + plugin_->name() + "': apply failed at frame " + std::to_string(in.index) + " (" +
                                  status_name(s) + "): " + (message && *message ? message : "no message"),
                              s);
    }
    if (out == nullptr) return nullptr;
    std::string why;
    if (out->color == nullptr || out->depth == nullptr)
        why = "an incomplete frame";
    else if (out->index != in.index)
        why = "frame " + std::to_string(out->index) + " for frame " + std::to_string(in.index);
    else if (!std::isfinite(out->timestamp) || !std::isfinite(out->depth_timestamp))
        why = "a stamp that is not finite";
    else
        why = frame_problem(*out, camera_);
    if (!why.empty())
        throw PluginCallError("filter '" + plugin_->name() + "' gave " + why + " at frame " + std::to_string(in.index), VOBENCH_ERROR);
    return out;
}

}  // namespace vobench
