// libFuzzer target: the list and calibration parsers of the dataset readers (TUM rgb.txt/depth.txt,
// PUTK² camData.txt, depth_camera.txt, matched.txt; ICL-NUIM associations.txt, camera.txt, POV-Ray
// .txt, .depth and .gt.sim) must parse or throw std::runtime_error.
#include "../../plugins/datasets/icl_nuim/icl_files.hpp"
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
        switch (data[0] % 9) {
            case 0: vobench::tum::parse_list(text, "fuzz"); break;
            case 1: vobench::putk2::parse_cam_data(text, "fuzz"); break;
            case 2: vobench::putk2::parse_depth_camera(text, "fuzz"); break;
            case 3: vobench::putk2::parse_matched(text, "fuzz"); break;
            case 4: vobench::icl::parse_associations(text, "fuzz"); break;
            case 5: vobench::icl::parse_camera(text, "fuzz"); break;
            case 6: vobench::icl::parse_camera_vectors(text, "fuzz"); break;
            case 7: vobench::icl::parse_ray_depth(text, "fuzz", 16); break;
            default: vobench::icl::parse_sim(text, "fuzz"); break;
        }
    } catch (const std::runtime_error&) {}
    return 0;
}
