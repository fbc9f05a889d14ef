/*
 * fault_plugin.c — deliberately broken plugins, one per FAULT_* value, for the loader's refusal tests
 * and for `vobench plugins check` on crashing code. Compiled once per fault (see CMakeLists.txt).
 */
#include <vobench/vobench_plugin.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FAULT_NO_ENTRY 1
#define FAULT_WRONG_ABI 2
#define FAULT_NULL_DESCRIPTOR 3
#define FAULT_BAD_STRUCT_SIZE 4
#define FAULT_BAD_PARAM_DEFAULT 5
#define FAULT_NULL_FUNCTION 6
#define FAULT_SEGFAULT 7
#define FAULT_HANG 8
#define FAULT_EXIT 9
/* The sweep's faults strike at frame 3, so that frames 0-2 show the partial trajectory kept. */
#define FAULT_ABORT 10
#define FAULT_MEMORY 11
#define FAULT_NAN_POSE 12
#define FAULT_ERROR_STATUS 13
#define FAULT_STDOUT_GARBAGE 14

struct vobench_odometry {
    int unused;
};

static vobench_odometry* f_create(const vobench_host_services* host) {
    (void)host;
    return (vobench_odometry*)calloc(1, sizeof(vobench_odometry));
}
static vobench_status f_start(vobench_odometry* self, const vobench_odometry_config* config) {
    (void)self;
    (void)config;
    return VOBENCH_OK;
}
static vobench_status f_process(vobench_odometry* self, const vobench_frame* frame, vobench_pose* pose, vobench_tracking_status* status) {
    (void)self;
    (void)frame;
#if FAULT == FAULT_SEGFAULT
    {
        volatile int* volatile nowhere = NULL;
        *nowhere = 42; /* SIGSEGV */
    }
#elif FAULT == FAULT_HANG
    for (;;) {}
#elif FAULT == FAULT_EXIT
    exit(3);
#elif FAULT == FAULT_ABORT
    if (frame->index == 3) abort();
#elif FAULT == FAULT_MEMORY
    if (frame->index == 3) {
        /* Touch 64 MB at a time until someone stops us; give up (an error) at 8 GB so a broken
         * memory limit cannot take the machine down. */
        static char* volatile keep; /* the blocks stay reachable: the allocation cannot be optimised away */
        size_t total = 0;
        while (total < ((size_t)8 << 30)) {
            char* block = (char*)malloc((size_t)64 << 20);
            if (block) memset(block, 1, (size_t)64 << 20);
            keep = block;
            total += (size_t)64 << 20;
        }
        return VOBENCH_ERROR;
    }
#elif FAULT == FAULT_NAN_POSE
    if (frame->index == 3) {
        pose->qw = 1.0;
        pose->tx = NAN;
        *status = VOBENCH_TRACKING_OK;
        return VOBENCH_OK;
    }
#elif FAULT == FAULT_ERROR_STATUS
    if (frame->index == 3) return VOBENCH_ERROR;
#elif FAULT == FAULT_STDOUT_GARBAGE
    {
        /* Binary and text noise on both streams: the harness must not read its results from them. */
        static const char noise[] = "\x00\xff{\"status\": \"ok\"}\nframe 3 FAILED\r\x1b[2J";
        fwrite(noise, 1, sizeof(noise), stdout);
        fwrite(noise, 1, sizeof(noise), stderr);
        fflush(stdout);
    }
#endif
    pose->qw = 1.0;
    *status = VOBENCH_TRACKING_OK;
    return VOBENCH_OK;
}
static const char* f_last_error(vobench_odometry* self) {
    (void)self;
#if FAULT == FAULT_ERROR_STATUS
    return "deliberate error status at frame 3";
#elif FAULT == FAULT_MEMORY
    return "allocated 8 GB without being stopped";
#else
    return "";
#endif
}
static void f_destroy(vobench_odometry* self) { free(self); }

static const vobench_odometry_api k_api = {sizeof(vobench_odometry_api),
                                           f_create,
                                           f_start,
#if FAULT == FAULT_NULL_FUNCTION
                                           NULL,
#else
                                           f_process,
#endif
                                           NULL,
                                           f_last_error,
                                           f_destroy};

static const vobench_param_desc k_params[] = {
    {sizeof(vobench_param_desc), "gain", VOBENCH_PARAM_DOUBLE,
#if FAULT == FAULT_BAD_PARAM_DEFAULT
     "not-a-number",
#else
     "1.0",
#endif
     0.0, 10.0, NULL, "a parameter"},
};

static const vobench_plugin_descriptor k_descriptor = {
#if FAULT == FAULT_BAD_STRUCT_SIZE
    8,
#else
    sizeof(vobench_plugin_descriptor),
#endif
    VOBENCH_ABI_VERSION,
    VOBENCH_API_VERSION,
    VOBENCH_KIND_ODOMETRY,
    "fault_plugin",
    "0.0.1",
    "A deliberately broken plugin for tests.",
    "MIT",
    NULL,
    1,
    k_params,
    NULL,
    &k_api};

#if FAULT == FAULT_NO_ENTRY
VOBENCH_EXPORT int some_other_function(void) { return 1; }
#elif FAULT == FAULT_WRONG_ABI
VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v2(uint32_t abi, uint32_t api) {
    (void)abi;
    (void)api;
    return &k_descriptor;
}
#else
VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t abi, uint32_t api) {
    (void)api;
    if (abi != VOBENCH_ABI_VERSION) return NULL;
#if FAULT == FAULT_NULL_DESCRIPTOR
    return NULL;
#else
    return &k_descriptor;
#endif
}
#endif
