// python_dataset — reads sequences with a Python class: `reader: python_dataset, options: {module: my_reader.py}`.
// The class's contract is in this folder's README.md; the bridge lives in plugins/common/python.
#include "python_bridges.hpp"

namespace {

class PythonDatasetPlugin : public vobench::sdk::Dataset {
public:
    static vobench::sdk::PluginInfo info() { return vobench::python::dataset_info(); }

    std::vector<vobench::sdk::Param> extra_params(const vobench::sdk::Params& given) override { return impl().extra_params(given); }
    void open(const std::string& path, const vobench::sdk::Params& options) override { impl().open(path, options); }
    const vobench_sequence_info& describe() override { return impl().describe(); }
    const vobench_frame& read_frame(uint64_t index) override { return impl().read_frame(index); }

private:
    vobench::sdk::Dataset& impl() {
        if (!impl_) impl_ = vobench::python::make_dataset(&host());
        return *impl_;
    }
    std::unique_ptr<vobench::sdk::Dataset> impl_;
};

}  // namespace

VOBENCH_DATASET_PLUGIN(PythonDatasetPlugin)
