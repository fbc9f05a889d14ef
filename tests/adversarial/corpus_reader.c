/*
 * corpus_reader.c — the dataset half of the adversarial corpus: a plain-C reader (no SDK) that makes
 * its sequence in memory, compiled once per fault (FAULT=<code>). FAULT 0 is healthy: 30 textured
 * 64x48 frames at 30 Hz, the camera moving 1 cm per frame along x (the ground truth). The path it is
 * given only names the sequence.
 */
#include <vobench/vobench_plugin.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The faults: FAULT is one of these numbers (tests/adversarial/CMakeLists.txt). */
#define HEALTHY 0
#define ZERO_FRAMES 1       /* declares no frames */
#define NAN_STAMP 2         /* frame 5 has a NaN stamp */
#define NAN_GROUND_TRUTH 3  /* ground-truth row 2 is NaN */
#define STAMPS_BACKWARDS 4  /* frame 4 is stamped before frame 3 */
#define LIES_ABOUT_COUNT 5  /* declares 30 frames, read_frame fails from frame 10 */
#define WRONG_SIZE 6        /* frame 3 is 32x24 where the camera is 64x48 */
#define NULL_CAMERA 7       /* describe() gives no camera */
#define NAN_FOCAL 8         /* fx is NaN */
#define CRASH_IN_READ 9     /* read_frame(5) dereferences NULL */
#define HANG_IN_OPEN 10     /* open() never returns */
#define GT_WITHOUT_ARRAY 11 /* gt_count 30, ground_truth NULL */
#define HOSTILE_NAME 12     /* the sequence's name holds a newline and a pose line (otherwise healthy) */
#define NULL_FRAME_DATA 13  /* frame 2's colour data pointer is NULL */

#ifndef FAULT
#define FAULT 0
#endif

#define W 64
#define H 48
#define N 30

struct vobench_dataset {
    vobench_camera camera;
    vobench_sequence_info info;
    double gt[N * 8];
    uint8_t rgb[W * H * 3];
    uint16_t depth[W * H];
    vobench_image color, depth_image;
    vobench_frame frame;
    char error[128];
};

static vobench_dataset* r_create(const vobench_host_services* host) {
    (void)host;
    return (vobench_dataset*)calloc(1, sizeof(vobench_dataset));
}

static vobench_status r_open(vobench_dataset* self, const char* path, const vobench_params* options) {
    (void)path;
    (void)options;
    if (FAULT == HANG_IN_OPEN)
        for (;;) pause();
    vobench_camera c = {sizeof(vobench_camera), W, H, 60.0, 60.0, 31.5, 23.5, VOBENCH_DISTORTION_NONE, 0, {0}};
    if (FAULT == NAN_FOCAL) c.fx = NAN;
    self->camera = c;
    for (int k = 0; k < N; ++k) {
        double* g = self->gt + 8 * k;
        g[0] = 1.0 + k / 30.0;
        g[1] = 0.01 * k;
        g[7] = 1.0;
    }
    if (FAULT == NAN_GROUND_TRUTH) self->gt[8 * 2 + 3] = NAN;
    vobench_sequence_info* i = &self->info;
    i->struct_size = sizeof(vobench_sequence_info);
    i->name = FAULT == HOSTILE_NAME ? "corpus\n1 2 3 4 0 0 0 1\n$(touch pwned)" : "corpus";
    i->sensor = "synthetic";
    i->camera = FAULT == NULL_CAMERA ? NULL : &self->camera;
    i->depth_width = W;
    i->depth_height = H;
    i->depth_scale = 1.0 / 5000.0;
    i->frame_count = FAULT == ZERO_FRAMES ? 0 : N;
    i->ground_truth = FAULT == GT_WITHOUT_ARRAY ? NULL : self->gt;
    i->gt_count = N;
    i->gt_position_sigma_m = 0;
    i->gt_rotation_sigma_deg = 0;
    return VOBENCH_OK;
}

static vobench_status r_describe(vobench_dataset* self, const vobench_sequence_info** out) {
    *out = &self->info;
    return VOBENCH_OK;
}

static vobench_status r_read_frame(vobench_dataset* self, uint64_t index, const vobench_frame** out) {
    if (index >= self->info.frame_count) {
        snprintf(self->error, sizeof self->error, "frame %llu is past the end", (unsigned long long)index);
        return VOBENCH_OUT_OF_RANGE;
    }
    if (FAULT == LIES_ABOUT_COUNT && index >= 10) {
        snprintf(self->error, sizeof self->error, "there is no frame %llu after all", (unsigned long long)index);
        return VOBENCH_IO_ERROR;
    }
    if (FAULT == CRASH_IN_READ && index == 5) {
        volatile int* volatile nowhere = NULL;
        *nowhere = 1;
    }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const uint8_t v = (uint8_t)((x + (int)index) * 37 ^ y * 91);
            self->rgb[(y * W + x) * 3 + 0] = self->rgb[(y * W + x) * 3 + 1] = self->rgb[(y * W + x) * 3 + 2] = v;
            self->depth[y * W + x] = (uint16_t)(5000 + 10 * y);
        }
    const int w = FAULT == WRONG_SIZE && index == 3 ? W / 2 : W, h = FAULT == WRONG_SIZE && index == 3 ? H / 2 : H;
    self->color = (vobench_image){sizeof(vobench_image), w, h, w * 3, VOBENCH_PIXEL_RGB8, self->rgb};
    if (FAULT == NULL_FRAME_DATA && index == 2) self->color.data = NULL;
    self->depth_image = (vobench_image){sizeof(vobench_image), w, h, w * 2, VOBENCH_PIXEL_DEPTH_U16, self->depth};
    double stamp = self->gt[8 * index];
    if (FAULT == NAN_STAMP && index == 5) stamp = NAN;
    if (FAULT == STAMPS_BACKWARDS && index == 4) stamp = self->gt[8 * 2];
    self->frame = (vobench_frame){sizeof(vobench_frame), index, stamp, stamp, &self->color, &self->depth_image, 1.0 / 5000.0};
    *out = &self->frame;
    return VOBENCH_OK;
}

static const char* r_last_error(vobench_dataset* self) { return self ? self->error : ""; }
static void r_destroy(vobench_dataset* self) { free(self); }

static const vobench_dataset_api k_api = {sizeof(vobench_dataset_api), r_create, r_open, r_describe, r_read_frame, r_last_error, r_destroy};

static const vobench_plugin_descriptor k_descriptor = {sizeof(vobench_plugin_descriptor),
                                                       VOBENCH_ABI_VERSION,
                                                       VOBENCH_API_VERSION,
                                                       VOBENCH_KIND_DATASET,
                                                       "corpus_reader",
                                                       "1.0",
                                                       "The adversarial corpus's reader (healthy: 30 frames, 1 cm per frame along x).",
                                                       "MIT",
                                                       NULL,
                                                       0,
                                                       NULL,
                                                       &k_api,
                                                       NULL};

VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t abi, uint32_t api) {
    (void)api;
    return abi == VOBENCH_ABI_VERSION ? &k_descriptor : NULL;
}
