/*
 * corpus_filter.c — the filter part of the adversarial corpus (API 3): a plain-C filter, compiled once
 * per fault (FAULT=<code>). FAULT 0 is healthy: it passes frames through. Each fault starts at frame 3.
 */
#include <vobench/vobench_plugin.h>

#include <stdlib.h>
#include <string.h>

#define HEALTHY 0
#define WRONG_SIZE 1   /* gives a frame half the camera's width */
#define WRONG_INDEX 2  /* gives frame 4 for frame 3 */
#define CRASH 3        /* dereferences NULL */
#define ERROR_STATUS 4 /* returns an error with a message */
#define NAN_STAMP 5    /* gives a frame with a NaN stamp */
#define DROP_ALL 6     /* drops every frame from frame 3: the plugin sees 3 frames */

#ifndef FAULT
#define FAULT 0
#endif

struct vobench_filter {
    vobench_image color;
    vobench_frame frame;
};

static vobench_filter* f_create(const vobench_host_services* host) {
    (void)host;
    return calloc(1, sizeof(vobench_filter));
}
static vobench_status f_start(vobench_filter* self, const vobench_filter_config* config) {
    (void)self;
    (void)config;
    return VOBENCH_OK;
}
static vobench_status f_apply(vobench_filter* self, const vobench_frame* in, const vobench_frame** out) {
    *out = in;
    if (FAULT == HEALTHY || in->index < 3) return VOBENCH_OK;
    self->frame = *in;
    self->color = *in->color;
    self->frame.color = &self->color;
    switch (FAULT) {
        case WRONG_SIZE: self->color.width /= 2; break;
        case WRONG_INDEX: self->frame.index += 1; break;
        case CRASH: *(volatile int*)0 = 1; break;
        case ERROR_STATUS: return VOBENCH_ERROR;
        case NAN_STAMP: self->frame.timestamp = 0.0 / 0.0; break;
        case DROP_ALL: *out = NULL; return VOBENCH_OK;
        default: break;
    }
    *out = &self->frame;
    return VOBENCH_OK;
}
static const char* f_last_error(vobench_filter* self) {
    (void)self;
    return FAULT == ERROR_STATUS ? "deliberately fails at frame 3" : "";
}
static void f_destroy(vobench_filter* self) { free(self); }

static const vobench_filter_api k_api = {sizeof(vobench_filter_api), f_create, f_start, f_apply, f_last_error, f_destroy};
static const vobench_plugin_descriptor k_descriptor = {sizeof(vobench_plugin_descriptor),
                                                       VOBENCH_ABI_VERSION,
                                                       VOBENCH_API_VERSION,
                                                       VOBENCH_KIND_FILTER,
                                                       "corpus_filter",
                                                       "1.0.0",
                                                       "adversarial corpus filter",
                                                       "MIT",
                                                       NULL,
                                                       0,
                                                       NULL,
                                                       NULL,
                                                       NULL,
                                                       &k_api};

VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t abi, uint32_t api) {
    return abi == VOBENCH_ABI_VERSION && api >= 3 ? &k_descriptor : NULL;
}
