// libFuzzer target: the list and calibration parsers of the dataset readers (TUM rgb.txt/depth.txt,
// PUTK² camData.txt, depth_camera.txt, matched.txt) must parse or throw std::runtime_error.
#include "../../plugins/datasets/putk2/putk2_files.hpp"
#include "tum_lists.hpp"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        switch (data[0] % 4) {
        case 0: vobench::tum::parse_list(text, "fuzz"); break;
        case 1: vobench::putk2::parse_cam_data(text, "fuzz"); break;
        case 2: vobench::putk2::parse_depth_camera(text, "fuzz"); break;
        default: vobench::putk2::parse_matched(text, "fuzz"); break;
        }
    } catch (const std::runtime_error&) {
    }
    return 0;
}
