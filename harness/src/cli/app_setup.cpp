#include "cli/app_setup.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace vobench::cli {

void setup_logging(CLI::App& app) {
    spdlog::set_default_logger(spdlog::stderr_color_mt("vobench"));
    spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    static bool verbose = false, quiet = false;
    app.add_flag("-v,--verbose", verbose, "More log output");
    app.add_flag("-q,--quiet", quiet, "Only warnings and errors");
    app.parse_complete_callback([] {
        spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
    });
}

int parse_and_run(CLI::App& app, int argc, char** argv, const int& exit_code) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
    return exit_code;
}

}  // namespace vobench::cli
