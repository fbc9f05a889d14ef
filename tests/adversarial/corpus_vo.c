/*
 * corpus_vo.c — the odometry half of the adversarial corpus: one plain-C plugin (no SDK), compiled
 * once per fault (FAULT=<code>, see CMakeLists.txt). FAULT 0 is healthy: it reports the camera moving
 * 1 cm along x per frame, exactly what corpus_reader's ground truth says. Every fault strikes at
 * frame 3 unless its name says otherwise, so frames 0-2 show what a partial trajectory keeps.
 */
#define _GNU_SOURCE
#include <vobench/vobench_plugin.h>

#include <dirent.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

/* The faults: FAULT is one of these numbers (tests/adversarial/CMakeLists.txt). */
#define HEALTHY 0
#define ENTRY_CRASH 1       /* the entry function dereferences NULL */
#define ENTRY_HANG 2        /* the entry function never returns */
#define CTOR_STDOUT 3       /* a library constructor prints to stdout (otherwise healthy) */
#define BAD_UTF8_STRINGS 4  /* version and description are invalid UTF-8 (otherwise healthy) */
#define CLOSE_FDS 5         /* closes every file descriptor at frame 10, then goes on */
#define HUGE_POSE 6         /* tx = 1e300: finite, absurd */
#define NAN_COUNTER 7       /* a counter of NaN */
#define MANY_COUNTERS 8     /* 80,000 distinct counter names in one call */
#define LONG_COUNTER_NAME 9 /* a 4 KB counter name */
#define FORK_CHILD 10       /* forks a child that sleeps for an hour */
#define FORK_ESCAPE 11      /* double fork + setsid: a daemon outside the cell's session */
#define KILL_PARENT 12      /* kill(getppid(), SIGTERM): the harness */
#define EXIT0 13            /* exit(0) inside process() */
#define BAD_QUATERNION 14   /* a quaternion of norm 2 */
#define NULL_LAST_ERROR 15  /* an error status, and last_error() returns NULL */
#define BAD_UTF8_ERROR 16   /* an error status with an invalid UTF-8 message */
#define LOG_FLOOD 17        /* writes 200 MB to stderr */
#define FORK_MEMORY 18      /* a forked child touches 1.5 GB: the group's memory counts */
#define UNKNOWN_STATUS 19   /* tracking status 7 */
#define CREATE_NULL 20      /* create() returns NULL */
#define START_ERROR 21      /* start() fails with a message */
#define FORGE_STREAM 22     /* writes a forged line into every file it has open */
#define HANG_IN_DESTROY 23  /* destroy() never returns */
#define ABORT_IN_DESTROY 24 /* destroy() aborts */
#define STACK_OVERFLOW 25   /* unbounded recursion */
#define RAISE_SIGTERM 26    /* raise(SIGTERM) on itself */
#define FORGE_SUCCESS 27    /* at frame 3 rewrites the cell's sequence.json (3 frames) and result.json ("ok"), then _exit(0) */

#ifndef FAULT
#define FAULT 0
#endif

struct vobench_odometry {
    const vobench_host_services* host;
    char error[256];
};

static void touch_memory(size_t bytes) {
    char* block = (char*)malloc(bytes);
    if (block) memset(block, 1, bytes);
    sleep(30);
    free(block);
}

static int recurse(int depth) {
    volatile char pad[4096];
    pad[0] = (char)depth;
    return recurse(depth + 1) + pad[0];
}

#if FAULT == CTOR_STDOUT
__attribute__((constructor)) static void noisy_constructor(void) {
    printf("{\"this\": \"is not vobench's output\"}\nplugin constructor says hello\n");
    fflush(stdout);
}
#endif

static vobench_odometry* c_create(const vobench_host_services* host) {
    if (FAULT == CREATE_NULL) return NULL;
    vobench_odometry* self = (vobench_odometry*)calloc(1, sizeof(vobench_odometry));
    if (self) self->host = host;
    return self;
}

static vobench_status c_start(vobench_odometry* self, const vobench_odometry_config* config) {
    (void)config;
    if (FAULT == START_ERROR) {
        snprintf(self->error, sizeof self->error, "deliberately refuses to start");
        return VOBENCH_ERROR;
    }
    return VOBENCH_OK;
}

static void forge_every_open_file(void) {
    DIR* d = opendir("/proc/self/fd");
    struct dirent* e;
    static const char forged[] = "{\"i\":0,\"t\":0,\"ns\":1,\"r\":0,\"s\":0,\"p\":[0,0,0,0,0,0,1]}\n";
    while (d && (e = readdir(d)) != NULL) {
        int fd = atoi(e->d_name);
        if (fd > 2) (void)!write(fd, forged, sizeof forged - 1);
    }
    if (d) closedir(d);
}

/* The folder of the cell's frame stream, found through the descriptors this process holds. */
static int cell_folder(char* out, size_t size) {
    DIR* d = opendir("/proc/self/fd");
    struct dirent* e;
    int found = 0;
    while (d && !found && (e = readdir(d)) != NULL) {
        char link[64], target[4096];
        snprintf(link, sizeof link, "/proc/self/fd/%s", e->d_name);
        ssize_t n = readlink(link, target, sizeof target - 1);
        if (n <= 0) continue;
        target[n] = '\0';
        char* slash = strrchr(target, '/');
        if (slash && strcmp(slash, "/frames.jsonl") == 0) {
            *slash = '\0';
            snprintf(out, size, "%s", target);
            found = 1;
        }
    }
    if (d) closedir(d);
    return found;
}

static void write_text(const char* folder, const char* name, const char* text) {
    char path[4200];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    FILE* f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static vobench_status c_process(vobench_odometry* self, const vobench_frame* frame, vobench_pose* pose, vobench_tracking_status* status) {
    const uint64_t i = frame->index;
    pose->tx = 0.01 * (double)i;
    pose->ty = pose->tz = 0.0;
    pose->qx = pose->qy = pose->qz = 0.0;
    pose->qw = 1.0;
    *status = VOBENCH_TRACKING_OK;
    if (FAULT == CLOSE_FDS && i == 10)
        for (int fd = 3; fd < 4096; ++fd) close(fd);
    if (i != 3) return VOBENCH_OK;
    switch (FAULT) {
        case HUGE_POSE: pose->tx = 1e300; break;
        case NAN_COUNTER: self->host->counter(self->host->context, "inliers", NAN); break;
        case MANY_COUNTERS: {
            char name[32];
            for (int k = 0; k < 80000; ++k) {
                snprintf(name, sizeof name, "c%d", k);
                self->host->counter(self->host->context, name, k);
            }
            break;
        }
        case LONG_COUNTER_NAME: {
            static char name[4097];
            memset(name, 'n', 4096);
            self->host->counter(self->host->context, name, 1);
            break;
        }
        case FORK_CHILD:
            if (fork() == 0) {
                sleep(3600);
                _exit(0);
            }
            break;
        case FORK_ESCAPE:
            if (fork() == 0) {
                setsid();
                if (fork() == 0) {
                    sleep(3600);
                    _exit(0);
                }
                _exit(0);
            }
            sleep(1); /* let the daemon be re-parented before the cell ends */
            break;
        case KILL_PARENT:
            kill(getppid(), SIGTERM);
            sleep(1);
            break;
        case EXIT0: exit(0);
        case BAD_QUATERNION: pose->qw = 2.0; break;
        case NULL_LAST_ERROR: return VOBENCH_ERROR;
        case BAD_UTF8_ERROR: snprintf(self->error, sizeof self->error, "bad \xff\xfe bytes \xc0\x80 in the message"); return VOBENCH_ERROR;
        case LOG_FLOOD: {
            static char line[1 << 16];
            memset(line, 'x', sizeof line);
            for (int k = 0; k < 200 * 16; ++k) (void)!write(2, line, sizeof line);
            break;
        }
        case FORK_MEMORY:
            if (fork() == 0) {
                touch_memory((size_t)1536 << 20);
                _exit(0);
            }
            sleep(5);
            break;
        case UNKNOWN_STATUS: *status = 7; break;
        case FORGE_STREAM: forge_every_open_file(); break;
        case STACK_OVERFLOW: return (vobench_status)recurse(0);
        case RAISE_SIGTERM: raise(SIGTERM); break;
        case FORGE_SUCCESS: {
            char folder[4096];
            if (cell_folder(folder, sizeof folder)) {
                write_text(folder, "sequence.json", "{\"name\": \"forged\", \"frames_to_run\": 3, \"frame_count\": 3, \"gt_count\": 30}\n");
                write_text(folder, "result.json", "{\"status\": \"ok\", \"error\": \"\", \"frames\": 3}\n");
            }
            _exit(0);
        }
        default: break;
    }
    return VOBENCH_OK;
}

static const char* c_last_error(vobench_odometry* self) {
    if (FAULT == NULL_LAST_ERROR) return NULL;
    return self ? self->error : "";
}

static void c_destroy(vobench_odometry* self) {
    if (self && FAULT == HANG_IN_DESTROY)
        for (;;) pause();
    if (self && FAULT == ABORT_IN_DESTROY) abort();
    free(self);
}

static const vobench_odometry_api k_api = {sizeof(vobench_odometry_api), c_create, c_start, c_process, NULL, c_last_error, c_destroy};

#if FAULT == BAD_UTF8_STRINGS
#define CORPUS_VERSION "1.\xff\xfe"
#define CORPUS_DESCRIPTION "an odometry plugin whose strings are not UTF-8: \xc3\x28 \xa0\xa1"
#else
#define CORPUS_VERSION "1.0"
#define CORPUS_DESCRIPTION "The adversarial corpus's odometry plugin (healthy: 1 cm per frame along x)."
#endif

static const vobench_plugin_descriptor k_descriptor = {sizeof(vobench_plugin_descriptor),
                                                       VOBENCH_ABI_VERSION,
                                                       VOBENCH_API_VERSION,
                                                       VOBENCH_KIND_ODOMETRY,
                                                       "corpus_vo",
                                                       CORPUS_VERSION,
                                                       CORPUS_DESCRIPTION,
                                                       "MIT",
                                                       NULL,
                                                       0,
                                                       NULL,
                                                       NULL,
                                                       &k_api};

VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t abi, uint32_t api) {
    (void)api;
    if (FAULT == ENTRY_CRASH) {
        volatile int* volatile nowhere = NULL;
        *nowhere = 1;
    }
    if (FAULT == ENTRY_HANG)
        for (;;) pause();
    return abi == VOBENCH_ABI_VERSION ? &k_descriptor : NULL;
}
