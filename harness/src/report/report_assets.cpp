#include "report/report_assets.hpp"

#include "report_asset_paths.h"  // generated: VOBENCH_PLOTLY_JS_PATH, VOBENCH_REPORT_APP_JS_PATH, VOBENCH_PLOTLY_VERSION

// The files go into .rodata as they are (the assembler's .incbin), each followed by a NUL; the
// symbols are hidden, so two copies of the library in one process cannot clash.
#define VOBENCH_EMBED(name, path)                                                                                              \
    __asm__(".section .rodata\n.balign 16\n.globl " #name "_begin\n.hidden " #name "_begin\n" #name "_begin:\n.incbin \"" path \
            "\"\n.globl " #name "_end\n.hidden " #name "_end\n" #name "_end:\n.byte 0\n.previous\n")

VOBENCH_EMBED(vobench_asset_plotly, VOBENCH_PLOTLY_JS_PATH);
VOBENCH_EMBED(vobench_asset_report_app, VOBENCH_REPORT_APP_JS_PATH);

extern "C" {
extern const char vobench_asset_plotly_begin[], vobench_asset_plotly_end[];
extern const char vobench_asset_report_app_begin[], vobench_asset_report_app_end[];
}

namespace vobench {

std::string_view plotly_js() {
    return {vobench_asset_plotly_begin, static_cast<std::size_t>(vobench_asset_plotly_end - vobench_asset_plotly_begin)};
}
std::string_view plotly_version() { return VOBENCH_PLOTLY_VERSION; }
std::string_view report_app_js() {
    return {vobench_asset_report_app_begin, static_cast<std::size_t>(vobench_asset_report_app_end - vobench_asset_report_app_begin)};
}

}  // namespace vobench
