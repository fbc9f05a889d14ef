#include "util/subprocess.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/process.hpp>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace vobench {
namespace bp = boost::process;

std::string ChildResult::describe() const {
    if (timed_out) return "timed out (killed)";
    if (exited) return "exited with code " + std::to_string(exit_code);
    std::string name = sigabbrev_np(signal) ? std::string("SIG") + sigabbrev_np(signal) : "?";
    return "killed by signal " + std::to_string(signal) + " (" + name + ")";
}

ChildResult run_self(const std::vector<std::string>& args, int timeout_s) {
    namespace fs = std::filesystem;
    const fs::path log = fs::temp_directory_path() /
                         ("vobench-child-" + std::to_string(::getpid()) + "-" +
                          std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".log");
    ChildResult result;
    {
        // Output goes to a file, not a pipe: a chatty child can never block on a full pipe.
        bp::child child(boost::dll::program_location(), bp::args(args), (bp::std_out & bp::std_err) > log.string(),
                        bp::std_in.close());
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
        std::error_code ec;
        while (child.running(ec) && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        if (child.running(ec)) {
            child.terminate(ec);  // SIGKILL
            result.timed_out = true;
        } else {
            const int status = child.native_exit_code();
            if (WIFEXITED(status)) {
                result.exited = true;
                result.exit_code = WEXITSTATUS(status);
            } else if (WIFSIGNALED(status)) {
                result.signal = WTERMSIG(status);
            }
        }
    }
    std::ifstream in(log);
    std::ostringstream ss;
    ss << in.rdbuf();
    result.output = ss.str();
    std::error_code ec;
    fs::remove(log, ec);
    return result;
}

}  // namespace vobench
