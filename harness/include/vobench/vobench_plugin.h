/*
 * vobench_plugin.h — the vobench plugin ABI, generation 1.
 *
 * This is the only header a plugin needs. It is plain C99 and valid C++; it depends on nothing but
 * <stdint.h>. A plugin is a shared library that exports exactly one symbol, VOBENCH_ENTRY_SYMBOL.
 *
 * ---------------------------------------------------------------------------------------------------
 * Versions
 *   VOBENCH_ABI_VERSION  the generation. It is part of the entry symbol's name, so a library built for
 *                        another generation simply has no symbol this host looks for. It changes only on
 *                        a breaking change, and host and plugin must agree exactly.
 *   VOBENCH_API_VERSION  grows with additive changes (a field appended to a struct, a function appended
 *                        to a table). Both sides use the smaller of the two versions they speak.
 *
 * Rules every struct follows
 *   - The first member is `uint32_t struct_size`, set by whoever fills the struct to sizeof() as that
 *     side was compiled. Fields are only ever appended. A reader touches a field only when
 *     `struct_size` covers it (VOBENCH_HAS_FIELD below). So an old plugin works with a new host and a
 *     new plugin with an old host.
 *   - Only fixed-width integers, double, `const char*`, pointers to these structs and function pointers
 *     cross the boundary. Enumerations are int32_t typedefs with #defined values.
 *   - Arrays of numbers are flat (e.g. 8 doubles per pose); arrays of structs are walked with a stride
 *     equal to the element's struct_size (VOBENCH_ARRAY_AT below).
 *
 * Ownership tags used on every pointer below
 *   [host-owned]    allocated and freed by the host; the plugin may read it during the call only,
 *                   unless a longer lifetime is written beside it.
 *   [plugin-owned]  allocated and freed by the plugin; the host reads it for the lifetime written
 *                   beside it and never frees it.
 *   [static]        lives as long as the library stays loaded.
 *
 * Thread rules
 *   - The entry function may be called from any thread, any number of times; it must return the same
 *     descriptor each time.
 *   - An instance (dataset or odometry handle) is used by one thread at a time; the host never calls
 *     two functions on one handle concurrently, but may move a handle between threads.
 *   - Distinct instances, of one plugin or of several, may be used concurrently from distinct threads.
 *     A plugin therefore keeps no mutable global state: two instances must never interfere.
 *   - Host services may be called from the thread that is inside a call from the host (only).
 *
 * Errors
 *   Every function that can fail returns a vobench_status. On failure the instance keeps a message
 *   retrievable with last_error(): [plugin-owned], valid until the next call on that instance. No
 *   exception, longjmp or exit() may cross this boundary (the C++ SDK in plugin.hpp catches every
 *   exception for you).
 *
 * Poses (the TUM RGB-D convention)
 *   A pose is camera-to-world: it maps a point in the camera frame (x right, y down, z forward, metres)
 *   into the world frame. Rotation is a unit quaternion stored x, y, z, w; translation in metres.
 *   Time stamps are double seconds; a data set without a clock uses the frame index as its stamp.
 * ---------------------------------------------------------------------------------------------------
 */
#ifndef VOBENCH_PLUGIN_H
#define VOBENCH_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ===== Versions and the entry symbol ============================================================ */

#define VOBENCH_ABI_VERSION 1u
/* API history: 1 — first release; 2 — vobench_sequence_info gains gt_position_sigma_m and
 * gt_rotation_sigma_deg (the reader's declared ground-truth accuracy); 3 — vobench_dataset_api and
 * vobench_odometry_api gain extra_params (parameters that depend on other parameters' values, as a
 * bridge to another language has: the Python bridge's module=FILE declares its own); a third kind,
 * VOBENCH_KIND_FILTER (a perturbation between reader and algorithm), with the descriptor's `filter`
 * table appended. */
#define VOBENCH_API_VERSION 3u

/* The name of the one exported function, with the ABI generation in it. */
#define VOBENCH_ENTRY_SYMBOL "vobench_plugin_entry_v1"

/* Marks the entry function as the library's only exported symbol (plugins build with hidden
 * visibility: see vobench_add_plugin() in cmake/). */
#if defined(_WIN32)
#define VOBENCH_EXPORT __declspec(dllexport)
#else
#define VOBENCH_EXPORT __attribute__((visibility("default")))
#endif

/* True when a struct filled by the other side, whose first member is struct_size, contains `field`. */
#define VOBENCH_HAS_FIELD(ptr, type, field) ((ptr)->struct_size >= offsetof(type, field) + sizeof(((type*)0)->field))

/* The i-th element of an array of structs whose elements all carry the same struct_size. */
#define VOBENCH_ARRAY_AT(base, type, i) ((const type*)((const char*)(base) + (size_t)(i) * (size_t)((base)->struct_size)))

/* ===== Status codes ============================================================================= */

typedef int32_t vobench_status;
#define VOBENCH_OK 0               /* success */
#define VOBENCH_ERROR 1            /* a failure not covered below; see last_error() */
#define VOBENCH_INVALID_ARGUMENT 2 /* a parameter, option or argument is malformed or out of range */
#define VOBENCH_IO_ERROR 3         /* a file is missing, unreadable, corrupt or malformed */
#define VOBENCH_OUT_OF_RANGE 4     /* e.g. a frame index past the end of the sequence */
#define VOBENCH_UNSUPPORTED 5      /* the plugin does not offer this (e.g. a sensor it cannot read) */
#define VOBENCH_CANCELLED 6        /* the host's cancel flag was seen */
#define VOBENCH_NO_MEMORY 7        /* an allocation failed */

/* ===== Descriptor: what a plugin is, readable without creating anything ========================= */

typedef int32_t vobench_plugin_kind;
#define VOBENCH_KIND_DATASET 1  /* a dataset reader: yields RGB-D frames and ground truth */
#define VOBENCH_KIND_ODOMETRY 2 /* an odometry algorithm: consumes frames, yields poses */
#define VOBENCH_KIND_FILTER 3   /* API 3: a perturbation between reader and algorithm (noise, holes, drops …) */

typedef int32_t vobench_param_type;
#define VOBENCH_PARAM_BOOL 1   /* "true"/"false" (also 1/0, on/off, yes/no) */
#define VOBENCH_PARAM_INT 2    /* decimal integer, within [min_value, max_value] */
#define VOBENCH_PARAM_DOUBLE 3 /* decimal number, finite, within [min_value, max_value] */
#define VOBENCH_PARAM_STRING 4 /* any text */
#define VOBENCH_PARAM_ENUM 5   /* one of the words of `choices` */

/* One tunable parameter. Every pointer is [static]. */
typedef struct vobench_param_desc {
    uint32_t struct_size;
    const char* name; /* identifier: [a-z0-9_]+ ; unique within the plugin */
    vobench_param_type type;
    const char* default_value; /* text form of the default; must itself be valid */
    double min_value;          /* INT/DOUBLE: inclusive range; ignored for other types */
    double max_value;
    const char* choices; /* ENUM: words separated by '|', e.g. "rgbd|icp"; else NULL */
    const char* help;    /* one sentence for `vobench plugins info` */
} vobench_param_desc;

struct vobench_dataset_api;
struct vobench_odometry_api;
struct vobench_filter_api;

/* The static descriptor the entry function returns. Every pointer is [static]. */
typedef struct vobench_plugin_descriptor {
    uint32_t struct_size;
    uint32_t abi_version; /* must be VOBENCH_ABI_VERSION */
    uint32_t api_version; /* the API version the plugin was built against */
    vobench_plugin_kind kind;
    const char* name;        /* identifier: [a-z0-9_]+, what configs and the CLI call it */
    const char* version;     /* the plugin's own version, e.g. "1.2.0" */
    const char* description; /* one or two sentences */
    const char* license;     /* SPDX identifier, e.g. "MIT" */
    const char* url;         /* home page or paper; may be NULL */
    uint32_t param_count;
    const vobench_param_desc* params; /* param_count elements (stride: params->struct_size); NULL if 0 */
    /* Exactly one of these is non-NULL, according to `kind` (`filter`: API 3, read only when
     * struct_size covers it; a filter's descriptor leaves dataset and odometry NULL). */
    const struct vobench_dataset_api* dataset;
    const struct vobench_odometry_api* odometry;
    const struct vobench_filter_api* filter;
} vobench_plugin_descriptor;

/* The entry point. The host passes the ABI and API versions it speaks. The plugin returns its
 * descriptor ([static]) or NULL when it cannot serve this host (e.g. it needs a newer API).
 * Thread-safe; must not allocate per call; must not fail in any other way. */
typedef const vobench_plugin_descriptor* (*vobench_plugin_entry_fn)(uint32_t host_abi_version, uint32_t host_api_version);

/* ===== Host services: what the host offers every instance ======================================= */

typedef int32_t vobench_log_level;
#define VOBENCH_LOG_DEBUG 0
#define VOBENCH_LOG_INFO 1
#define VOBENCH_LOG_WARNING 2
#define VOBENCH_LOG_ERROR 3

/* Passed to create(); [host-owned], valid until that instance's destroy(). Call the functions only
 * from inside a call the host made on that instance. `context` is opaque to the plugin. */
typedef struct vobench_host_services {
    uint32_t struct_size;
    void* context;
    /* A message for the run log. `message` is [plugin-owned] and read during the call only. */
    void (*log)(void* context, vobench_log_level level, const char* message);
    /* Time a named stage of the current call (e.g. "detection"). Stages may nest and may repeat within
     * a call; times add up per name per frame. `stage` is read during the call only. */
    void (*stage_begin)(void* context, const char* stage);
    void (*stage_end)(void* context, const char* stage);
    /* A per-frame counter (e.g. "features_tracked" = 312): the last value set in a call is recorded. */
    void (*counter)(void* context, const char* name, double value);
    /* Non-zero when the host asks the plugin to stop early; the plugin then returns VOBENCH_CANCELLED. */
    int32_t (*is_cancelled)(void* context);
} vobench_host_services;

/* ===== Images, frames, cameras, poses =========================================================== */

typedef int32_t vobench_pixel_format;
#define VOBENCH_PIXEL_RGB8 1      /* 3 bytes per pixel, R G B */
#define VOBENCH_PIXEL_BGR8 2      /* 3 bytes per pixel, B G R (OpenCV's order) */
#define VOBENCH_PIXEL_GRAY8 3     /* 1 byte per pixel */
#define VOBENCH_PIXEL_DEPTH_U16 4 /* uint16 per pixel, metres = value * depth_scale, 0 = no reading */
#define VOBENCH_PIXEL_DEPTH_F32 5 /* float per pixel, metres = value * depth_scale, 0 or NaN = none */

typedef struct vobench_image {
    uint32_t struct_size;
    int32_t width;
    int32_t height;
    int32_t stride_bytes; /* bytes from one row to the next, >= width * bytes per pixel */
    vobench_pixel_format format;
    const void* data; /* lifetime: that of the frame it belongs to */
} vobench_image;

/* One RGB-D frame. In API 1, depth is registered to the colour camera and has the colour image's
 * width and height (readers register and rescale as their sensor needs).
 * Lifetime: a frame returned by a dataset reader and everything it points to is [plugin-owned] by the
 * reader, valid until the next read_frame() or destroy() on that reader. A frame passed to an odometry
 * plugin is [host-owned] and borrowed for the duration of process() only: copy what you keep. */
typedef struct vobench_frame {
    uint32_t struct_size;
    uint64_t index;             /* 0-based position in the sequence */
    double timestamp;           /* colour stamp, seconds (or the index, for clock-less data) */
    double depth_timestamp;     /* stamp of the depth image paired with it */
    const vobench_image* color; /* never NULL */
    const vobench_image* depth; /* never NULL */
    double depth_scale;         /* metres per depth unit, e.g. 1/5000 for TUM, 1/1000 for PUTK² */
} vobench_frame;

typedef int32_t vobench_distortion_model;
#define VOBENCH_DISTORTION_NONE 0   /* images are already undistorted */
#define VOBENCH_DISTORTION_OPENCV 1 /* OpenCV order k1 k2 p1 p2 k3 k4 k5 k6 (rational model) */

/* A pinhole camera. fx or fy may be negative where a data set's convention flips an axis; the
 * readers in this repository present positive focal lengths (see each reader's README). */
typedef struct vobench_camera {
    uint32_t struct_size;
    int32_t width;
    int32_t height;
    double fx, fy, cx, cy; /* pixels */
    vobench_distortion_model distortion_model;
    int32_t distortion_count; /* 0..8 meaningful entries of `distortion` */
    double distortion[8];
} vobench_camera;

typedef struct vobench_pose {
    uint32_t struct_size;
    double timestamp;      /* seconds */
    double tx, ty, tz;     /* metres, camera-to-world */
    double qx, qy, qz, qw; /* unit quaternion, camera-to-world */
} vobench_pose;

/* Parameters as text, validated by the host against the descriptor's table before create().
 * keys/values: [host-owned] arrays of `count` strings each, valid during the call only. */
typedef struct vobench_params {
    uint32_t struct_size;
    uint32_t count;
    const char* const* keys;
    const char* const* values;
} vobench_params;

/* ===== Dataset readers ========================================================================== */

typedef struct vobench_dataset vobench_dataset; /* opaque, [plugin-owned] */

/* What a reader says about an open sequence. [plugin-owned], valid until destroy(). */
typedef struct vobench_sequence_info {
    uint32_t struct_size;
    const char* name;             /* sequence name, e.g. "rgbd_dataset_freiburg1_rpy" */
    const char* sensor;           /* e.g. "kinect1", "kinect2", "xtion", "synthetic" */
    const vobench_camera* camera; /* colour camera, the frame geometry delivered to plugins */
    int32_t depth_width;          /* the depth sensor's native size before registration */
    int32_t depth_height;
    double depth_scale; /* metres per depth unit of delivered frames */
    uint64_t frame_count;
    /* Ground truth: gt_count poses, 8 doubles each: t tx ty tz qx qy qz qw (camera-to-world, TUM).
     * NULL when the sequence has none. Never given to odometry plugins by the host. */
    const double* ground_truth;
    uint64_t gt_count;
    /* API 2. The declared 1σ accuracy of the ground truth (Ceriani et al. 2009: ground truth has an error
     * of its own): position in metres, rotation in degrees. 0: exact (rendered data); negative: not
     * known. A host reads them only when struct_size covers them; an API-1 reader means "not known". */
    double gt_position_sigma_m;
    double gt_rotation_sigma_deg;
} vobench_sequence_info;

typedef struct vobench_dataset_api {
    uint32_t struct_size;
    /* Create a reader instance. `host` as described above. Returns NULL only on allocation failure. */
    vobench_dataset* (*create)(const vobench_host_services* host);
    /* Open the sequence at `path` (a folder or file, [host-owned], read during the call) with options
     * validated against the descriptor's table. Called once per instance. May take long (indexing). */
    vobench_status (*open)(vobench_dataset* self, const char* path, const vobench_params* options);
    /* Describe the open sequence; *out is [plugin-owned], valid until destroy(). */
    vobench_status (*describe)(vobench_dataset* self, const vobench_sequence_info** out);
    /* Decode frame `index` (0 <= index < frame_count). *out is [plugin-owned], valid until the next
     * read_frame() or destroy() on this instance. Frames may be read in any order. */
    vobench_status (*read_frame)(vobench_dataset* self, uint64_t index, const vobench_frame** out);
    /* The message of the last failed call; [plugin-owned], valid until the next call on `self`.
     * Never NULL (empty when there was no error). */
    const char* (*last_error)(vobench_dataset* self);
    /* Free everything the instance owns. `self` may be NULL. */
    void (*destroy)(vobench_dataset* self);
    /* API 3; may be NULL (the descriptor's table is then all there is). The options this instance takes
     * beyond the descriptor's table, which depend on the values of some of the table's own (`given`:
     * [host-owned], read during the call; it holds only names of the descriptor's table, already
     * validated). Called after create() and before open(), at most once per instance. On success *count
     * and *params ([plugin-owned], valid until destroy(); stride params->struct_size) describe them,
     * by the rules of the descriptor's table, with names distinct from it. The host validates the options
     * it passes to open() against both tables. */
    vobench_status (*extra_params)(vobench_dataset* self, const vobench_params* given, uint32_t* count, const vobench_param_desc** params);
} vobench_dataset_api;

/* ===== Odometry algorithms ====================================================================== */

typedef struct vobench_odometry vobench_odometry; /* opaque, [plugin-owned] */

typedef int32_t vobench_tracking_status;
#define VOBENCH_TRACKING_OK 0 /* the pose is an estimate for this frame */
#define VOBENCH_TRACKING_LOST                                                                     \
    1                             /* tracking failed at this frame; the pose is the plugin's best \
                                   * guess (often the last good one) and the plugin will try to go on */
#define VOBENCH_TRACKING_FAILED 2 /* the plugin cannot go on without reset(); the pose is the last one */

typedef struct vobench_odometry_config {
    uint32_t struct_size;
    const vobench_camera* camera; /* [host-owned], read during start() only: copy it */
    const vobench_params* params; /* [host-owned], read during start() only */
    uint64_t seed;                /* for any randomness (RANSAC ...): same seed, same trajectory */
} vobench_odometry_config;

typedef struct vobench_odometry_api {
    uint32_t struct_size;
    /* Create an instance; NULL only on allocation failure. */
    vobench_odometry* (*create)(const vobench_host_services* host);
    /* Configure before the first frame. Called once per instance. */
    vobench_status (*start)(vobench_odometry* self, const vobench_odometry_config* config);
    /* Consume one frame ([host-owned], borrowed for this call) and write the camera-to-world pose of
     * this frame into *pose ([host-owned]; the host sets pose->struct_size and the plugin writes only
     * the fields it covers; the first frame's pose defines the world frame, usually identity) and the
     * tracking status into *status. A non-OK return is an error that ends the run. This is the call the
     * host times. */
    vobench_status (*process)(vobench_odometry* self, const vobench_frame* frame, vobench_pose* pose, vobench_tracking_status* status);
    /* Forget all state but the configuration (the next frame starts a new world frame).
     * May be NULL when the plugin cannot reset. */
    vobench_status (*reset)(vobench_odometry* self);
    /* As for datasets: [plugin-owned], valid until the next call on `self`; never NULL. */
    const char* (*last_error)(vobench_odometry* self);
    /* Free everything the instance owns. `self` may be NULL. */
    void (*destroy)(vobench_odometry* self);
    /* API 3; may be NULL. As extra_params of vobench_dataset_api: the parameters beyond the descriptor's
     * table given the values of some of its own, called after create() and before start(); the host
     * validates the parameters it passes to start() against both tables. */
    vobench_status (*extra_params)(vobench_odometry* self, const vobench_params* given, uint32_t* count, const vobench_param_desc** params);
} vobench_odometry_api;

/* ===== Filters (API 3) =========================================================================== */

/* A filter sits between the reader and the odometry plugin and perturbs each frame — noise, holes,
 * blur, drops — so that a method's degradation can be measured on any data set. The host runs the
 * filters of a cell in order on every frame before it reaches the plugin, outside the timed window. */
typedef struct vobench_filter vobench_filter; /* opaque, [plugin-owned] */

typedef struct vobench_filter_config {
    uint32_t struct_size;
    const vobench_camera* camera; /* [host-owned], read during start() only: the frames' camera */
    const vobench_params* params; /* [host-owned], read during start() only */
    uint64_t seed;                /* for the perturbation's randomness: same seed, same frames */
    /* [host-owned], writable during start() only; preset to *camera. A filter that changes the frames'
     * geometry (resolution_scale) writes the camera of the frames it will give; the next filter and the
     * odometry plugin get that camera. */
    vobench_camera* output_camera;
} vobench_filter_config;

typedef struct vobench_filter_api {
    uint32_t struct_size;
    /* Create an instance; NULL only on allocation failure. */
    vobench_filter* (*create)(const vobench_host_services* host);
    /* Configure before the first frame. Called once per instance. */
    vobench_status (*start)(vobench_filter* self, const vobench_filter_config* config);
    /* Perturb frame `in` ([host-owned], valid until the frame has reached the odometry plugin) into
     * *out: a frame of the filter's ([plugin-owned], valid until the next apply() or destroy() on this
     * instance), or `in` itself when it leaves the frame as it is; with the camera's width and height,
     * the same index, and pixel formats a reader may deliver. Or set *out = NULL to drop the frame (it is
     * then not given to the plugin and has no pose). Frames come in order, each once. */
    vobench_status (*apply)(vobench_filter* self, const vobench_frame* in, const vobench_frame** out);
    /* As for the other kinds: [plugin-owned], valid until the next call on `self`; never NULL. */
    const char* (*last_error)(vobench_filter* self);
    /* Free everything the instance owns. `self` may be NULL. */
    void (*destroy)(vobench_filter* self);
} vobench_filter_api;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* VOBENCH_PLUGIN_H */
