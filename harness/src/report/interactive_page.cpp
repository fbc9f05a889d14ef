#include "report/interactive_page.hpp"

#include "report/report_assets.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <stdexcept>

namespace vobench {

std::string page_head_security() {
    // plotly compiles its WebGL shaders' wrappers at run time ('unsafe-eval'); connect-src, font-src,
    // frame-src and every other fetch fall under default-src 'none'.
    return "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline' 'unsafe-eval'; "
           "style-src 'unsafe-inline'; img-src data: blob:; worker-src blob:\">\n"
           "<script>window.vobenchCspViolations=0;document.addEventListener('securitypolicyviolation',function(e){"
           "window.vobenchCspViolations++;document.body.dataset.cspViolations=String(window.vobenchCspViolations);"
           "document.body.dataset.cspBlocked=String(e.blockedURI).slice(0,200);});</script>\n";
}

std::string interactive_scripts(const nlohmann::json& data) {
    std::string island;
    for (char c : json_text(data, -1)) {
        if (c == '<')
            island += "\\u003c";
        else if (c == '>')
            island += "\\u003e";
        else if (c == '&')
            island += "\\u0026";
        else
            island += c;
    }
    // A script's text cannot hold "</script" (it would end the element) nor "<!--" (the parser's escaped
    // states); neither library has one, checked so that a future version cannot slip one in.
    const std::string_view plotly = plotly_js(), app = report_app_js();
    for (std::string_view bad : {"</script", "<!--"})
        if (plotly.find(bad) != std::string_view::npos || app.find(bad) != std::string_view::npos)
            throw std::runtime_error("an embedded script contains " + std::string(bad) + ": it cannot be inlined");
    return "<script type=\"application/json\" id=\"vobench-data\">" + island + "</script>\n<script>/* " + std::string(plotly_version()) +
           " */\n" + std::string(plotly) + "\n</script>\n<script>\n" + std::string(app) + "\n</script>\n";
}

const char* explorer_style() {
    return ".viewer3d{width:100%;height:560px;border:1px solid #ddd}.chart{width:100%}.slider-bar{margin:0.5em 0;display:flex;gap:1em;"
           "align-items:center}.slider-bar input{flex:1}.frame-info{font-size:0.9em;min-width:40%}#filters label{margin-right:1.5em}"
           "tr.pickable{cursor:pointer}tr.pickable:hover td{background:#eef5fb}tr.picked td{background:#dcebf7}"
           ".view-note,.timing-note{font-size:0.85em;color:#555}";
}

void write_trajectory_page(const nlohmann::json& view, const std::string& title, const std::filesystem::path& out) {
    nlohmann::json v = view;
    v["title"] = clean_text(title);
    const nlohmann::json data = {{"kind", "plot"}, {"views", nlohmann::json::array({v})}};
    const std::string page = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n" + page_head_security() + "<title>" +
                             html_text(title) + "</title>\n<style>body{font-family:system-ui,sans-serif;margin:1em 2em;color:#222}" +
                             explorer_style() + "</style></head>\n<body>\n<section id=\"explorer\"></section>\n" +
                             interactive_scripts(data) + "</body></html>\n";
    write_file_atomic(out, page);
}

}  // namespace vobench
