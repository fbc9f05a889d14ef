#include "python_runtime.hpp"

#include "bridge_helpers_source.hpp"  // kBridgeHelpersSource, generated from bridge_helpers.py

#include <pybind11/embed.h>

#include <dlfcn.h>

#include <cstdlib>
#include <map>
#include <mutex>

namespace vobench::python {
namespace {

thread_local const sdk::Host* t_host = nullptr;

// vobench.stage("matching"): a context manager that times a stage of the current call.
class Stage {
public:
    explicit Stage(std::string name) : name_(std::move(name)) {}
    void enter() {
        host_ = t_host;
        if (host_) host_->stage_begin(name_.c_str());
    }
    void exit(const py::args&) {
        if (host_) host_->stage_end(name_.c_str());
        host_ = nullptr;
    }

private:
    std::string name_;
    const sdk::Host* host_ = nullptr;
};

}  // namespace

HostScope::HostScope(const sdk::Host* host) : previous_(t_host) { t_host = host; }
HostScope::~HostScope() { t_host = previous_; }

}  // namespace vobench::python

// The module user code imports: `import vobench`. Registered before the interpreter starts (this
// library's static initialisers run when it is loaded).
PYBIND11_EMBEDDED_MODULE(vobench, m) {
    namespace py = pybind11;
    using vobench::python::Stage;
    using vobench::python::t_host;
    m.doc() = "vobench host services for Python plugins: stage timing, counters, the run log.";
    py::class_<Stage>(m, "stage", "with vobench.stage('matching'): ... times a named stage of the current frame")
        .def(py::init<std::string>(), py::arg("name"))
        .def(
            "__enter__",
            [](Stage& s) -> Stage& {
                s.enter();
                return s;
            },
            py::return_value_policy::reference)
        .def("__exit__", &Stage::exit);
    m.def(
        "counter",
        [](const std::string& name, double value) {
            if (t_host) t_host->counter(name.c_str(), value);
        },
        py::arg("name"), py::arg("value"), "Records a per-frame counter (the last value set in a call is kept).");
    m.def(
        "log",
        [](const std::string& message, const std::string& level) {
            if (!t_host) return;
            const vobench_log_level l = level == "debug"     ? VOBENCH_LOG_DEBUG
                                        : level == "warning" ? VOBENCH_LOG_WARNING
                                        : level == "error"   ? VOBENCH_LOG_ERROR
                                                             : VOBENCH_LOG_INFO;
            t_host->log(l, message);
        },
        py::arg("message"), py::arg("level") = "info", "A line for the run log (level: debug, info, warning, error).");
    m.def(
        "cancelled", [] { return t_host != nullptr && t_host->cancelled(); }, "True when the host asks the plugin to stop early.");
}

namespace vobench::python {

void ensure_interpreter() {
    static std::once_flag once;
    static std::string failure;
    std::call_once(once, [] {
        // This library was loaded with RTLD_LOCAL, and libpython with it; numpy's and cv2's extension
        // modules expect libpython's symbols in the global scope, as in the python3 executable.
        Dl_info where{};
        if (dladdr(reinterpret_cast<void*>(&Py_IsInitialized), &where) != 0 && where.dli_fname != nullptr)
            dlopen(where.dli_fname, RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
        if (Py_IsInitialized()) {
            failure = "a Python interpreter already runs in this process (not started by vobench)";
            return;
        }
        try {
            // Without a program name, CPython takes the first python3 on PATH as its own and its prefix
            // as the standard library's: under pyenv or a venv that is another Python's, without the
            // packages of this libpython (Debian's python3-numpy, python3-opencv). So: the interpreter
            // this library was built with, or $VOBENCH_PYTHON (a venv's python of the same version).
            const char* env = std::getenv("VOBENCH_PYTHON");
            const std::string program = env && *env ? env : VOBENCH_PYTHON_EXECUTABLE;
            PyConfig config;
            PyConfig_InitPythonConfig(&config);
            config.install_signal_handlers = 0;  // SIGINT and the rest belong to the host
            config.parse_argv = 0;
            const PyStatus status = PyConfig_SetBytesString(&config, &config.program_name, program.c_str());
            if (PyStatus_Exception(status)) {
                PyConfig_Clear(&config);
                failure = "Python did not start: program name " + program;
                return;
            }
            py::initialize_interpreter(&config, 0, nullptr, false);
            py::module_::import("sys").attr("dont_write_bytecode") = true;
        } catch (const std::exception& e) {
            failure = std::string("Python did not start: ") + e.what();
            return;
        }
        PyEval_SaveThread();  // release the GIL: each call takes it
    });
    if (!failure.empty()) throw sdk::Error(VOBENCH_ERROR, failure);
}

py::module_ helpers() {
    static py::module_* cached = nullptr;  // GIL held: no race
    if (cached == nullptr) {
        py::module_ m = py::module_::import("types").attr("ModuleType")("vobench_bridge_helpers");
        py::exec(kBridgeHelpersSource, m.attr("__dict__"));
        py::module_::import("sys").attr("modules")["vobench_bridge_helpers"] = m;
        cached = new py::module_(m);  // lives as long as the interpreter (never finalised)
    }
    return *cached;
}

std::string describe(py::error_already_set& e) {
    try {
        return helpers().attr("describe_error")(e.type(), e.value(), e.trace()).cast<std::string>();
    } catch (const std::exception&) {
        return e.what();
    }
}

UserClass load_user_class(const std::string& module, const std::string& name) {
    UserClass user;
    user.cls = helpers().attr("load_class")(module, name);
    user.rows = helpers().attr("declared_params")(user.cls);
    static const std::map<std::string, vobench_param_type> types = {{"bool", VOBENCH_PARAM_BOOL},
                                                                    {"int", VOBENCH_PARAM_INT},
                                                                    {"double", VOBENCH_PARAM_DOUBLE},
                                                                    {"string", VOBENCH_PARAM_STRING},
                                                                    {"enum", VOBENCH_PARAM_ENUM}};
    for (const py::handle row : user.rows) {
        const auto t = row.cast<py::tuple>();
        sdk::Param p;
        p.name = t[0].cast<std::string>();
        p.type = types.at(t[1].cast<std::string>());
        p.default_value = t[2].cast<std::string>();
        p.min_value = t[3].cast<double>();
        p.max_value = t[4].cast<double>();
        p.choices = t[5].cast<std::string>();
        p.help = t[6].cast<std::string>();
        user.params.push_back(std::move(p));
    }
    return user;
}

py::dict typed_values(const UserClass& user, const sdk::Params& all) {
    py::dict text;
    for (const sdk::Param& p : user.params) text[py::str(p.name)] = all.get_string(p.name);
    return helpers().attr("typed_values")(user.rows, text);
}

std::vector<sdk::Param> bridge_params(const char* default_class, const char* kind) {
    return {{"module", VOBENCH_PARAM_STRING, "", 0, 0, "",
             std::string("the Python ") + kind + ": a .py file (relative to the working folder) or a dotted module name on PYTHONPATH"},
            {"class", VOBENCH_PARAM_STRING, default_class, 0, 0, "", std::string("the class in it that implements the ") + kind}};
}

}  // namespace vobench::python
