// instances.hpp — RAII owners of plugin instances, in host terms.
//
// Each owns the handle, the host services it was created with, and a reference to its library (so
// the code stays mapped while the instance lives). Every failed call throws PluginCallError with the
// plugin's name, the call, the status and the plugin's own message.
#pragma once

#include "abi/host_context.hpp"
#include "abi/params.hpp"
#include "abi/plugin_library.hpp"

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vobench {

class PluginCallError : public std::runtime_error {
public:
    PluginCallError(const std::string& message, vobench_status status) : std::runtime_error(message), status_(status) {}
    vobench_status status() const { return status_; }

private:
    vobench_status status_;
};

// Checks names, types and ranges against the plugin's table; throws std::invalid_argument naming the
// plugin and parameter.
void validate_params(const PluginInfo& plugin, const ParamMap& params);

// The entries of `params` whose names are in the descriptor's own table (the first table_size rows):
// what a plugin's extra_params() is given.
ParamMap table_params(const PluginInfo& plugin, const ParamMap& params);

// Keeps strings alive and presents them as vobench_params.
class ParamView {
public:
    explicit ParamView(const ParamMap& params);
    const vobench_params* get() const { return &view_; }

private:
    std::vector<std::string> keys_, values_;
    std::vector<const char*> key_ptrs_, value_ptrs_;
    vobench_params view_{};
};

const char* status_name(vobench_status status);

// Why a reader's frame does not match its camera (sizes, pixel formats, strides, depth scale), or "".
std::string frame_problem(const vobench_frame& frame, const vobench_camera& camera);

class DatasetInstance {
public:
    explicit DatasetInstance(PluginPtr plugin);
    ~DatasetInstance();
    DatasetInstance(const DatasetInstance&) = delete;
    DatasetInstance& operator=(const DatasetInstance&) = delete;

    // The plugin's parameter table extended by what this instance declares for the values in `options`
    // (API 3 extra_params; asked once per instance, the answer kept); the plain table otherwise.
    // Throws PluginCallError when the plugin fails or answers with a malformed table.
    const PluginInfo& params_for(const ParamMap& options);
    // Validates `options` against params_for(options), then opens.
    void open(const std::string& path, const ParamMap& options);
    const vobench_sequence_info& info() const { return *info_; }
    // Valid until the next read() or destruction.
    const vobench_frame& read(uint64_t index);
    const PluginLibrary& plugin() const { return *plugin_; }

private:
    [[noreturn]] void fail(const char* call, vobench_status status) const;
    PluginPtr plugin_;
    const vobench_dataset_api* api_;
    std::unique_ptr<HostContext> host_;
    vobench_dataset* handle_ = nullptr;
    const vobench_sequence_info* info_ = nullptr;
    std::optional<PluginInfo> params_;
};

class OdometryInstance {
public:
    explicit OdometryInstance(PluginPtr plugin);
    ~OdometryInstance();
    OdometryInstance(const OdometryInstance&) = delete;
    OdometryInstance& operator=(const OdometryInstance&) = delete;

    // As DatasetInstance::params_for.
    const PluginInfo& params_for(const ParamMap& params);
    // Validates `params` against params_for(params), then starts.
    void start(const vobench_camera& camera, const ParamMap& params, uint64_t seed);
    // The raw call, for the timed loop: returns the status, throws nothing. On failure, last_error()
    // has the message.
    vobench_status process(const vobench_frame& frame, vobench_pose& pose, vobench_tracking_status& tracking) {
        return api_->process(handle_, &frame, &pose, &tracking);
    }
    std::string last_error() const;
    bool can_reset() const { return api_->reset != nullptr; }
    void reset();
    HostContext& host() { return *host_; }
    const PluginLibrary& plugin() const { return *plugin_; }

private:
    PluginPtr plugin_;
    const vobench_odometry_api* api_;
    std::unique_ptr<HostContext> host_;
    vobench_odometry* handle_ = nullptr;
    std::optional<PluginInfo> params_;
};

// A filter (API 3): perturbs frames between reader and odometry plugin.
class FilterInstance {
public:
    explicit FilterInstance(PluginPtr plugin);
    ~FilterInstance();
    FilterInstance(const FilterInstance&) = delete;
    FilterInstance& operator=(const FilterInstance&) = delete;

    // Validates `params` against the table, then starts; `camera` is kept to check the frames it gives.
    void start(const vobench_camera& camera, const ParamMap& params, uint64_t seed);
    // The perturbed frame (valid until the next apply() or destruction), or nullptr when the filter
    // drops it. Throws PluginCallError when the filter fails or gives a frame that is not `in`'s
    // (another index, a size or format that does not match the camera, a stamp that is not finite).
    const vobench_frame* apply(const vobench_frame& in);
    // The camera of the frames apply() gives (the filter may change the geometry), after start().
    const vobench_camera& output_camera() const { return camera_; }
    const PluginLibrary& plugin() const { return *plugin_; }

private:
    PluginPtr plugin_;
    const vobench_filter_api* api_;
    std::unique_ptr<HostContext> host_;
    vobench_filter* handle_ = nullptr;
    vobench_camera camera_{};
};

}  // namespace vobench
