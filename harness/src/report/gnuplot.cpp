#include "report/gnuplot.hpp"

#include "util/escape.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <cstdlib>
#include <sstream>

extern char** environ;

namespace vobench::gnuplot {
namespace fs = std::filesystem;

// Draws the figure in three formats from one plot body. `noenhanced`: names with _ or ^ print as written.
std::string script(const std::string& stem, const std::string& setup, const std::string& plot, int width, int height) {
    return fmt::format(
        "# {0}: written by vobench; edit and run `gnuplot {0}.gp` in this folder to restyle.\n"
        "set encoding utf8\n{1}\n"
        "set terminal pngcairo noenhanced size {2},{3} font 'Sans,10'\nset output '{0}.png'\n{4}\n"
        "set terminal svg noenhanced size {2},{3} font 'Sans,10'\nset output '{0}.svg'\n{4}\n"
        "set terminal pdfcairo noenhanced size {5:.2f}in,{6:.2f}in font 'Sans,8'\nset output '{0}.pdf'\n{4}\nunset output\n",
        stem, setup, width, height, plot, width / 100.0, height / 100.0);
}

// Looked up on PATH, as posix_spawnp will.
bool available() {
    static const bool found = [] {
        const char* path = std::getenv("PATH");
        std::istringstream dirs(path ? path : "/usr/bin:/bin");
        for (std::string dir; std::getline(dirs, dir, ':');)
            if (!dir.empty() && ::access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
        return false;
    }();
    return found;
}

bool run(const fs::path& folder, const std::string& stem) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (stem + ".log").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::string exe = "gnuplot", script_name = stem + ".gp";
    char* argv[] = {exe.data(), script_name.data(), nullptr};
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) return false;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(folder / (stem + ".png"));
    if (ok)
        fs::remove(folder / (stem + ".log"));
    else
        spdlog::warn("gnuplot failed on {}: see {}", (folder / (stem + ".gp")).string(), (folder / (stem + ".log")).string());
    return ok;
}

// A label in a gnuplot data file: double-quoted, and gnuplot reads no escapes there, so a quote in
// the name becomes an apostrophe.
std::string data_label(const std::string& text) {
    std::string label = clean_text(text);
    for (char& c : label)
        if (c == '"') c = '\'';
    return "\"" + label + "\"";
}

const char* colour(std::size_t k) {
    static const char* const palette[] = {"#0072B2", "#E69F00", "#009E73", "#D55E00", "#56B4E9", "#CC79A7", "#F0E442"};
    return palette[k % (sizeof palette / sizeof palette[0])];
}

}  // namespace vobench::gnuplot
