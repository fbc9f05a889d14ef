#include "abi/conformance.hpp"

#include "abi/host_context.hpp"
#include "abi/instances.hpp"
#include "abi/plugin_library.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace vobench {
namespace {

class Report {
public:
    explicit Report(std::ostream& out) : out_(out) {}
    void pass(const std::string& step) { out_ << "ok    " << step << std::endl; }
    void fail(const std::string& step, const std::string& why) {
        out_ << "FAIL  " << step << ": " << why << std::endl;
        ++failures_;
    }
    void check(bool ok, const std::string& step, const std::string& why) { ok ? pass(step) : fail(step, why); }
    void step(const std::string& name) { out_ << "..    " << name << std::endl; }
    int failures() const { return failures_; }

private:
    std::ostream& out_;
    int failures_ = 0;
};

bool nonempty(const char* s) { return s != nullptr && *s != '\0'; }

// A plugin's message, safe to print: NULL is "(NULL)", invalid UTF-8 replaced.
std::string message_of(const char* s) { return s == nullptr ? "(NULL)" : clean_text(s); }

// A textured 160×120 frame with a slanted plane in front of the camera, so that any odometry has
// something to chew on.
struct SyntheticFrame {
    std::vector<uint8_t> rgb;
    std::vector<uint16_t> depth;
    vobench_image color{}, depth_image{};
    vobench_frame frame{};
    SyntheticFrame(uint64_t index, int shift) {
        const int w = 160, h = 120;
        rgb.resize(w * h * 3);
        depth.resize(w * h);
        std::mt19937 rng(7);
        std::vector<uint8_t> texture((w + 64) * h);
        for (auto& t : texture) t = static_cast<uint8_t>(rng() & 0xff);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint8_t v = texture[y * (w + 64) + x + shift];
                rgb[(y * w + x) * 3 + 0] = rgb[(y * w + x) * 3 + 1] = rgb[(y * w + x) * 3 + 2] = v;
                depth[y * w + x] = static_cast<uint16_t>(5000 + 10 * y);  // 1 m to 1.24 m at 1/5000 m
            }
        color = {sizeof(vobench_image), w, h, w * 3, VOBENCH_PIXEL_RGB8, rgb.data()};
        depth_image = {sizeof(vobench_image), w, h, w * 2, VOBENCH_PIXEL_DEPTH_U16, depth.data()};
        frame = {sizeof(vobench_frame), index, 0.1 * double(index), 0.1 * double(index), &color, &depth_image, 1.0 / 5000.0};
    }
};

// API 3: the parameters an instance declares for the given values, checked like the descriptor's.
template <typename Instance>
void check_extra_params(const PluginPtr& plugin, const ParamMap& given, Report& r) {
    if (!plugin->info().has_extra_params) return;
    r.step("extra parameters for " + std::to_string(given.size()) + " given value(s)");
    try {
        Instance instance(plugin);
        const PluginInfo& info = instance.params_for(given);
        r.pass("extra_params gave " + std::to_string(info.params.size() - info.table_size) + " well-formed parameter(s)");
        for (std::size_t k = info.table_size; k < info.params.size(); ++k)
            r.check(!info.params[k].help.empty(), "parameter '" + info.params[k].name + "' documented", "no help text");
    } catch (const std::exception& e) {
        r.fail("extra parameters", e.what());
    }
}

void check_odometry(const PluginPtr& plugin, const ParamMap& given, Report& r) {
    const vobench_odometry_api* api = plugin->descriptor().odometry;
    HostContext host(plugin->name());
    for (int round = 1; round <= 2; ++round) {
        r.step("create/destroy #" + std::to_string(round));
        vobench_odometry* h = api->create(host.services());
        r.check(h != nullptr, "create #" + std::to_string(round), "create() returned NULL");
        if (h) api->destroy(h);
    }
    api->destroy(nullptr);
    r.pass("destroy(NULL)");

    vobench_camera camera{sizeof(vobench_camera), 160, 120, 130.0, 130.0, 79.5, 59.5, VOBENCH_DISTORTION_NONE, 0, {0}};
    if (!plugin->params().empty()) {
        r.step("start with an unknown parameter");
        vobench_odometry* h = api->create(host.services());
        const char* keys[] = {"no_such_parameter_xyz"};
        const char* values[] = {"1"};
        vobench_params bad{sizeof(vobench_params), 1, keys, values};
        vobench_odometry_config config{sizeof(config), &camera, &bad, 1};
        const vobench_status s = api->start(h, &config);
        r.check(s != VOBENCH_OK && nonempty(api->last_error(h)), "an unknown parameter is refused with a message",
                s == VOBENCH_OK ? "start() accepted it" : "last_error() is empty");
        api->destroy(h);
    }
    check_extra_params<OdometryInstance>(plugin, given, r);
    const std::string with = given.empty() ? "defaults" : std::to_string(given.size()) + " given parameter(s)";
    r.step("start with " + with + " and process 5 synthetic frames");
    vobench_odometry* h = api->create(host.services());
    const ParamView view(given);
    if (plugin->info().has_extra_params) {  // the host asks before start(), as a cell does
        uint32_t count = 0;
        const vobench_param_desc* table = nullptr;
        const ParamView table_view(table_params(plugin->info(), given));
        api->extra_params(h, table_view.get(), &count, &table);
    }
    vobench_odometry_config config{sizeof(config), &camera, view.get(), 1};
    vobench_status s = api->start(h, &config);
    r.check(s == VOBENCH_OK, "start with " + with, std::string("status ") + status_name(s) + ": " + message_of(api->last_error(h)));
    if (s == VOBENCH_OK) {
        for (int k = 0; k < 5; ++k) {
            SyntheticFrame f(k, 2 * k);
            vobench_pose pose{};
            pose.struct_size = sizeof(pose);
            vobench_tracking_status tracking = -1;
            const std::string step = "process frame " + std::to_string(k);
            r.step(step);
            host.begin_call();
            s = api->process(h, &f.frame, &pose, &tracking);
            if (s != VOBENCH_OK) {
                r.check(nonempty(api->last_error(h)), step + " (error status comes with a message)", "empty last_error()");
                break;
            }
            const double qn = std::sqrt(pose.qx * pose.qx + pose.qy * pose.qy + pose.qz * pose.qz + pose.qw * pose.qw);
            const bool finite = std::isfinite(pose.tx) && std::isfinite(pose.ty) && std::isfinite(pose.tz) && std::isfinite(qn);
            r.check(finite && std::abs(qn - 1.0) < 1e-6, step + " gives a finite pose with a unit quaternion",
                    "pose not finite or quaternion norm " + std::to_string(qn));
            r.check(tracking >= VOBENCH_TRACKING_OK && tracking <= VOBENCH_TRACKING_FAILED, step + " tracking status",
                    "unknown tracking status " + std::to_string(tracking));
            r.check(host.unbalanced_stages() == 0, step + " stages balanced", "a stage was begun and not ended");
        }
        if (api->reset) {
            s = api->reset(h);
            r.check(s == VOBENCH_OK || s == VOBENCH_UNSUPPORTED, "reset", std::string("status ") + status_name(s));
        }
    }
    api->destroy(h);
}

void check_filter(const PluginPtr& plugin, const ParamMap& given, Report& r) {
    const vobench_filter_api* api = plugin->descriptor().filter;
    HostContext host(plugin->name());
    for (int round = 1; round <= 2; ++round) {
        r.step("create/destroy #" + std::to_string(round));
        vobench_filter* h = api->create(host.services());
        r.check(h != nullptr, "create #" + std::to_string(round), "create() returned NULL");
        if (h) api->destroy(h);
    }
    api->destroy(nullptr);
    r.pass("destroy(NULL)");
    r.step("start and filter 5 synthetic frames");
    try {
        FilterInstance f(plugin);
        const vobench_camera camera{sizeof(vobench_camera), 160, 120, 130.0, 130.0, 79.5, 59.5, VOBENCH_DISTORTION_NONE, 0, {0}};
        f.start(camera, given, 1);
        r.pass("start");
        for (int k = 0; k < 5; ++k) {
            SyntheticFrame in(k, 2 * k);
            const vobench_frame* out = f.apply(in.frame);  // checks index, size, formats, stamps
            r.pass("frame " + std::to_string(k) + (out ? " filtered, well-formed" : " dropped"));
        }
    } catch (const std::exception& e) {
        r.fail("filter the synthetic frames", e.what());
    }
}

void check_dataset(const PluginPtr& plugin, const ConformanceOptions& options, Report& r) {
    check_extra_params<DatasetInstance>(plugin, options.params, r);
    const vobench_dataset_api* api = plugin->descriptor().dataset;
    HostContext host(plugin->name());
    for (int round = 1; round <= 2; ++round) {
        r.step("create/destroy #" + std::to_string(round));
        vobench_dataset* h = api->create(host.services());
        r.check(h != nullptr, "create #" + std::to_string(round), "create() returned NULL");
        if (h) api->destroy(h);
    }
    api->destroy(nullptr);
    r.pass("destroy(NULL)");
    {
        r.step("open a missing path");
        vobench_dataset* h = api->create(host.services());
        vobench_params none{sizeof(vobench_params), 0, nullptr, nullptr};
        const vobench_status s = api->open(h, "/nonexistent/vobench-conformance", &none);
        r.check(s != VOBENCH_OK && nonempty(api->last_error(h)), "a missing path is refused with a message",
                s == VOBENCH_OK ? "open() succeeded" : "last_error() is empty");
        api->destroy(h);
    }
    if (!options.dataset_path) {
        r.pass("no --dataset-path given: reading a real sequence skipped");
        return;
    }
    r.step("open " + *options.dataset_path);
    try {
        DatasetInstance d(plugin);
        d.open(*options.dataset_path, options.params);
        const vobench_sequence_info& info = d.info();
        r.check(info.frame_count > 0, "sequence has frames", "frame_count is 0");
        const vobench_camera& cam = *info.camera;
        r.check(cam.width > 0 && cam.height > 0 && std::isfinite(cam.fx) && cam.fx != 0, "camera is sane", "bad camera");
        const uint64_t last = info.frame_count - 1;
        for (uint64_t index : {uint64_t{0}, last, uint64_t{0}}) {
            const vobench_frame& f = d.read(index);
            r.check(f.color->width == cam.width && f.color->height == cam.height && f.depth->width == cam.width &&
                        f.depth->height == cam.height,
                    "frame " + std::to_string(index) + " has the camera's size", "size differs from the camera");
        }
        bool refused = false;
        try {
            d.read(info.frame_count);
        } catch (const PluginCallError&) {
            refused = true;
        }
        r.check(refused, "reading past the end is refused", "read_frame(frame_count) succeeded");
    } catch (const std::exception& e) {
        r.fail("read the sequence", e.what());
    }
}

}  // namespace

int run_conformance(const ConformanceOptions& options, std::ostream& out) {
    Report r(out);
    r.step("load " + options.library.string());
    PluginPtr plugin;
    try {
        plugin = PluginLibrary::load(options.library);
    } catch (const PluginLoadError& e) {
        r.fail("load", e.what());
        out << "FAIL " << options.library.string() << " (refused)" << std::endl;
        if (!options.verdict_file.empty()) write_file_atomic(options.verdict_file, "1");
        return 1;
    }
    const vobench_plugin_descriptor& d = plugin->descriptor();
    r.pass(std::string("entry ") + VOBENCH_ENTRY_SYMBOL + ", descriptor valid: " + d.name + " " + d.version + " (" + kind_name(d.kind) +
           ", API " + std::to_string(d.api_version) + ", " + std::to_string(d.param_count) + " parameters)");
    r.check(plugin->entry()(VOBENCH_ABI_VERSION, VOBENCH_API_VERSION) == &d, "entry returns the same descriptor twice",
            "a different pointer the second time");
    r.check(plugin->entry()(VOBENCH_ABI_VERSION + 1, VOBENCH_API_VERSION) == nullptr, "entry refuses another ABI (NULL)",
            "it returned a descriptor for ABI " + std::to_string(VOBENCH_ABI_VERSION + 1));
    r.check(plugin->entry()(VOBENCH_ABI_VERSION, VOBENCH_API_VERSION + 100) != nullptr, "entry serves a newer host API",
            "it returned NULL for a newer API version");
    for (const sdk::Param& p : plugin->params()) r.check(!p.help.empty(), "parameter '" + p.name + "' documented", "no help text");
    if (d.kind == VOBENCH_KIND_ODOMETRY)
        check_odometry(plugin, options.params, r);
    else if (d.kind == VOBENCH_KIND_FILTER)
        check_filter(plugin, options.params, r);
    else
        check_dataset(plugin, options, r);
    out << (r.failures() == 0 ? "PASS " : "FAIL ") << options.library.string() << " (" << r.failures() << " failures)" << std::endl;
    if (!options.verdict_file.empty()) write_file_atomic(options.verdict_file, r.failures() == 0 ? "0" : "1");
    return r.failures() == 0 ? 0 : 1;
}

int check_in_child(const ConformanceOptions& options, std::ostream& out) {
    const std::filesystem::path verdict = std::filesystem::temp_directory_path() /
                                          ("vobench-check-" + std::to_string(::getpid()) + "-" + file_stem(options.library.string()));
    std::error_code ec;
    std::filesystem::remove(verdict, ec);
    std::vector<std::string> args = {"plugins", "check", "--in-process", options.library.string(), "--verdict", verdict.string()};
    if (options.dataset_path) {
        args.push_back("--dataset-path");
        args.push_back(*options.dataset_path);
    }
    for (const auto& [k, v] : options.params) {
        args.push_back("--param");
        args.push_back(k + "=" + v);
    }
    const ChildResult child = run_self(args, options.timeout_s);
    std::string written;
    try {
        written = read_file(verdict);
    } catch (const std::exception&) {
        // no verdict: the check did not reach its end
    }
    std::filesystem::remove(verdict, ec);
    out << clean_text(child.output, true);
    const bool finished = child.exited && (child.exit_code == 0 || child.exit_code == 1) && written == std::to_string(child.exit_code);
    if (finished && child.left_behind > 0) {
        // What a sweep fails a cell for (cell_supervisor.cpp): a plugin must not outlive its process.
        out << "FAIL  " << options.library.string() << ": left " << child.left_behind << " process" << (child.left_behind == 1 ? "" : "es")
            << " running after the check ended (killed)\n"
            << "FAIL " << options.library.string() << std::endl;
        return 1;
    }
    if (finished) return child.exit_code;
    // The last step line the child printed is where the plugin was.
    std::string last;
    std::size_t pos = 0;
    while (pos < child.output.size()) {
        std::size_t end = child.output.find('\n', pos);
        if (end == std::string::npos) end = child.output.size();
        if (end > pos && child.output.compare(pos, 2, "..") == 0) last = child.output.substr(pos, end - pos);
        pos = end + 1;
    }
    const std::string how =
        child.exited && written.empty() ? "the process ended (" + child.describe() + ") inside a plugin call" : child.describe();
    out << "FAIL  " << options.library.string() << ": " << how << (last.size() > 6 ? " — last step: " + clean_text(last.substr(6)) : "")
        << "\n"
        << "FAIL " << options.library.string() << std::endl;
    return 1;
}

}  // namespace vobench
