#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

// The harness runs `vobench <internal command>` children (plugin probes, cells): in this test binary
// they must be the vobench CLI, not the test binary itself.
int main(int argc, char** argv) {
    ::setenv("VOBENCH_EXECUTABLE", VOBENCH_CLI, 1);
    return Catch::Session().run(argc, argv);
}
