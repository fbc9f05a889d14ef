// python_bridges.hpp — the two Python bridges, as the plugins see them.
//
// Both live in one shared library, libvobench_python_runtime.so (next to the plugins, in runtime/),
// because a process may load the odometry bridge (`python`) and the reader bridge (`python_dataset`)
// at once: CPython has one interpreter per process, and pybind11 one registry of types, so one copy of
// the embedding code must own them. The plugins are thin: each forwards its SDK class to these.
// Only plain C++ and SDK types cross this header (no pybind11 type), so it is free of Python headers.
#pragma once

#include <vobench/plugin.hpp>

#include <memory>

#define VOBENCH_PYTHON_API __attribute__((visibility("default")))

namespace vobench::python {

// The descriptor info of the odometry bridge: parameters module, class (the rest declared by the
// class's PARAMS, through extra_params).
VOBENCH_PYTHON_API sdk::PluginInfo odometry_info();
VOBENCH_PYTHON_API std::unique_ptr<sdk::Odometry> make_odometry(const sdk::Host* host);

VOBENCH_PYTHON_API sdk::PluginInfo dataset_info();
VOBENCH_PYTHON_API std::unique_ptr<sdk::Dataset> make_dataset(const sdk::Host* host);

}  // namespace vobench::python
