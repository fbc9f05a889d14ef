/*
 * c_example — a vobench odometry plugin written in plain C99 against vobench_plugin.h alone.
 *
 * It estimates nothing clever: it integrates a constant velocity given as parameters (vx, vy, vz in
 * m/s along the world axes) from the frame stamps. Its purpose is to show every part of the C ABI:
 * the versioned entry, the static descriptor with a parameter table, an opaque handle with its own
 * error message, host services (a stage and a counter), parameter parsing, and ownership.
 */
#include <vobench/vobench_plugin.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct vobench_odometry {
    const vobench_host_services* host; /* [host-owned], valid until destroy */
    double velocity[3];
    double first_stamp;
    int have_first;
    char error[256];
};

static const vobench_param_desc k_params[] = {
    {sizeof(vobench_param_desc), "vx", VOBENCH_PARAM_DOUBLE, "0", -10.0, 10.0, NULL, "constant velocity along world x, m/s"},
    {sizeof(vobench_param_desc), "vy", VOBENCH_PARAM_DOUBLE, "0", -10.0, 10.0, NULL, "constant velocity along world y, m/s"},
    {sizeof(vobench_param_desc), "vz", VOBENCH_PARAM_DOUBLE, "0", -10.0, 10.0, NULL, "constant velocity along world z, m/s"},
};

static vobench_odometry* c_create(const vobench_host_services* host) {
    vobench_odometry* self = (vobench_odometry*)calloc(1, sizeof(vobench_odometry));
    if (self != NULL) self->host = host;
    return self;
}

static int parse_number(const char* text, double* out) {
    char* end = NULL;
    errno = 0;
    *out = strtod(text, &end);
    return errno == 0 && end != text && *end == '\0' && isfinite(*out);
}

static vobench_status c_start(vobench_odometry* self, const vobench_odometry_config* config) {
    uint32_t i;
    self->error[0] = '\0';
    self->velocity[0] = self->velocity[1] = self->velocity[2] = 0.0;
    if (config == NULL || config->params == NULL) return VOBENCH_OK;
    for (i = 0; i < config->params->count; ++i) {
        const char* key = config->params->keys[i];
        double value;
        int axis = strcmp(key, "vx") == 0 ? 0 : strcmp(key, "vy") == 0 ? 1 : strcmp(key, "vz") == 0 ? 2 : -1;
        if (axis < 0) {
            snprintf(self->error, sizeof self->error, "unknown parameter '%s'", key);
            return VOBENCH_INVALID_ARGUMENT;
        }
        if (!parse_number(config->params->values[i], &value) || fabs(value) > 10.0) {
            snprintf(self->error, sizeof self->error, "parameter '%s': '%s' is not a number in [-10, 10]", key, config->params->values[i]);
            return VOBENCH_INVALID_ARGUMENT;
        }
        self->velocity[axis] = value;
    }
    return VOBENCH_OK;
}

static vobench_status c_process(vobench_odometry* self, const vobench_frame* frame, vobench_pose* pose, vobench_tracking_status* status) {
    double dt;
    self->error[0] = '\0';
    if (self->host && self->host->stage_begin) self->host->stage_begin(self->host->context, "integrate");
    if (!self->have_first) {
        self->first_stamp = frame->timestamp;
        self->have_first = 1;
    }
    dt = frame->timestamp - self->first_stamp;
    /* Every field up to qw exists in API 1, whose pose struct the host always passes at least. */
    pose->timestamp = frame->timestamp;
    pose->tx = self->velocity[0] * dt;
    pose->ty = self->velocity[1] * dt;
    pose->tz = self->velocity[2] * dt;
    pose->qx = pose->qy = pose->qz = 0.0;
    pose->qw = 1.0;
    *status = VOBENCH_TRACKING_OK;
    if (self->host && self->host->stage_end) self->host->stage_end(self->host->context, "integrate");
    if (self->host && self->host->counter) self->host->counter(self->host->context, "elapsed_s", dt);
    return VOBENCH_OK;
}

static vobench_status c_reset(vobench_odometry* self) {
    self->have_first = 0;
    return VOBENCH_OK;
}

static const char* c_last_error(vobench_odometry* self) { return self->error; }

static void c_destroy(vobench_odometry* self) { free(self); }

/* extra_params (API 3): NULL, this plugin's table is all it takes. */
static const vobench_odometry_api k_api = {
    sizeof(vobench_odometry_api), c_create, c_start, c_process, c_reset, c_last_error, c_destroy, NULL};

static const vobench_plugin_descriptor k_descriptor = {
    sizeof(vobench_plugin_descriptor),
    VOBENCH_ABI_VERSION,
    VOBENCH_API_VERSION,
    VOBENCH_KIND_ODOMETRY,
    "c_example",
    "1.0.0",
    "Example plugin in plain C: integrates a constant velocity given as parameters.",
    "MIT",
    NULL,
    sizeof k_params / sizeof k_params[0],
    k_params,
    NULL,
    &k_api,
    NULL, /* filter: this is an odometry plugin */
};

VOBENCH_EXPORT const vobench_plugin_descriptor* vobench_plugin_entry_v1(uint32_t host_abi_version, uint32_t host_api_version) {
    if (host_abi_version != VOBENCH_ABI_VERSION || host_api_version < 1) return NULL;
    return &k_descriptor;
}
