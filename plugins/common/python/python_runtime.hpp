// python_runtime.hpp — the embedded interpreter and what both bridges do with it (internal to
// libvobench_python_runtime.so).
//
// The interpreter starts once per process, on the first bridge instance, and is never finalised
// (CPython cannot restart one with numpy in it). It runs without the GIL held between calls, so that
// any thread the host calls from can take it: every entry into Python holds a py::gil_scoped_acquire.
#pragma once

#include <vobench/plugin.hpp>

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace vobench::python {
namespace py = pybind11;

// Starts the interpreter (without Python's signal handlers: the host owns signals) and makes
// libpython's symbols global, so that extension modules (numpy, cv2), which are not linked against
// libpython, resolve. Thread-safe; throws sdk::Error when Python cannot start.
void ensure_interpreter();

// The bridge's helper module (bridge_helpers.py, embedded at build time). GIL held.
py::module_ helpers();

// The Python exception `e` as a failure reason: its type and message and the last frames of its
// traceback (file, line, code). GIL held.
std::string describe(py::error_already_set& e);

// Runs `body` with the GIL held; a Python exception becomes sdk::Error(VOBENCH_ERROR, "<what>: <traceback>").
template <typename Body>
auto with_python(const std::string& what, Body&& body) -> decltype(body()) {
    py::gil_scoped_acquire gil;
    try {
        return body();
    } catch (py::error_already_set& e) {
        throw sdk::Error(VOBENCH_ERROR, what + ":\n" + describe(e));
    } catch (const py::cast_error& e) {
        throw sdk::Error(VOBENCH_ERROR, what + ": " + e.what());
    }
}

// A user class and the parameters its PARAMS declares, read once (GIL held).
struct UserClass {
    py::object cls;
    py::object rows;  // bridge_helpers.declared_params(cls)
    std::vector<sdk::Param> params;
};
UserClass load_user_class(const std::string& module, const std::string& name);

// The declared parameters' values, typed (bool/int/float/str), from the validated `all`. GIL held.
py::dict typed_values(const UserClass& user, const sdk::Params& all);

// The host of the call running on this thread, for vobench.stage/counter/log; restored on exit.
class HostScope {
public:
    explicit HostScope(const sdk::Host* host);
    ~HostScope();
    HostScope(const HostScope&) = delete;
    HostScope& operator=(const HostScope&) = delete;

private:
    const sdk::Host* previous_;
};

// The two parameters every bridge has.
std::vector<sdk::Param> bridge_params(const char* default_class, const char* kind);

}  // namespace vobench::python
