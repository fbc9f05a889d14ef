// vobench new-plugin NAME [--dir DIR] — a ready-to-build out-of-tree plugin project, from the template.
#include "cli/commands.hpp"
#include "metrics/trajectory_io.hpp"
#include "plugin_template.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>

namespace vobench::cli {
namespace fs = std::filesystem;

namespace {

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t pos = 0; (pos = text.find(from, pos)) != std::string::npos; pos += to.size()) text.replace(pos, from.size(), to);
    return text;
}

// my_vo -> MyVo
std::string camel(const std::string& name) {
    std::string out;
    bool up = true;
    for (char c : name) {
        if (c == '_') {
            up = true;
            continue;
        }
        out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        up = false;
    }
    return out;
}

// NAME.py from the Python template, and a README that says how to check and run it.
void write_python_project(const fs::path& out, const std::string& name) {
    std::string source = plugin_template::kPython;
    source = replace_all(source, "The smallest vobench odometry plugin in Python",
                         name + " — a vobench odometry plugin in Python, made from the smallest one");
    source = replace_all(source, "template.py", name + ".py");
    const fs::path file = out / (name + ".py");
    write_file_atomic(file, source);
    write_file_atomic(out / "README.md",
                      fmt::format("# {0}\n\nA vobench odometry plugin in Python, run by the `python` bridge plugin (no build step):\n\n"
                                  "```sh\nvobench plugins info python --param module={1}\n"
                                  "vobench plugins check python --param module={1}\n"
                                  "vobench track --dataset tum --path SEQUENCE --algorithm python --param module={1}\n```\n\n"
                                  "In a config: `- {{name: {0}, plugin: python, params: {{module: {1}}}}}`.\n",
                                  name, file.string()));
    std::cout << fmt::format("wrote {0} and {1}/README.md\nnext: vobench plugins check python --param module={0}\n", file.string(),
                             out.string());
}

}  // namespace

void add_new_plugin_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("new-plugin", "Write a ready-to-build out-of-tree odometry plugin project from the template");
    static std::string name, dir;
    static bool python = false;
    c->add_option("NAME", name, "Plugin name: lower-case letters, digits and _")->required();
    c->add_option("--dir", dir, "Project folder (default: ./NAME); must not exist or be empty");
    c->add_flag("--python", python, "A Python plugin (NAME.py, run by the python bridge) instead of a C++ project");
    c->callback([&exit_code] {
        if (name.empty() ||
            !std::all_of(name.begin(), name.end(),
                         [](char ch) {
                             return std::islower(static_cast<unsigned char>(ch)) || std::isdigit(static_cast<unsigned char>(ch)) ||
                                    ch == '_';
                         }) ||
            std::isdigit(static_cast<unsigned char>(name[0])))
            throw CLI::ValidationError("NAME", "'" + name + "' is not a plugin name ([a-z_][a-z0-9_]*)");
        const fs::path out = dir.empty() ? fs::path(name) : fs::path(dir);
        if (fs::exists(out) && !fs::is_empty(out)) throw std::runtime_error(out.string() + ": exists and is not empty");
        fs::create_directories(out);
        if (python) {
            write_python_project(out, name);
            exit_code = 0;
            return;
        }
        std::string source = plugin_template::kSource;
        source = replace_all(source, "TemplateVo", camel(name));
        source = replace_all(source, "\"template\"", "\"" + name + "\"");
        source = replace_all(source, "// template — the smallest complete", "// " + name + " — made from the smallest complete");
        std::string cmake = plugin_template::kCMakeLists;
        cmake = replace_all(cmake, "vobench_template_plugin", name);
        cmake = replace_all(cmake, "vobench_add_plugin(template SOURCES template_vo.cpp)",
                            "vobench_add_plugin(" + name + " SOURCES " + name + ".cpp)");
        write_file_atomic(out / (name + ".cpp"), source);
        write_file_atomic(out / "CMakeLists.txt", cmake);
        write_file_atomic(out / "README.md",
                          fmt::format("# {0}\n\nA vobench odometry plugin. Build against an installed vobench SDK:\n\n"
                                      "```sh\ncmake -S . -B build -DCMAKE_PREFIX_PATH=/path/to/vobench/prefix\ncmake --build build\n"
                                      "vobench plugins check build/vobench_{0}.so\n"
                                      "VOBENCH_PLUGIN_PATH=build vobench track --dataset tum --path SEQUENCE --algorithm {0}\n```\n",
                                      name));
        std::cout << fmt::format(
            "wrote {0}/{1}.cpp, {0}/CMakeLists.txt and {0}/README.md\n"
            "next: cmake -S {0} -B {0}/build -DCMAKE_PREFIX_PATH=<vobench prefix> && cmake --build {0}/build\n",
            out.string(), name);
        exit_code = 0;
    });
}

}  // namespace vobench::cli
