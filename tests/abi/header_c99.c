/* The public header compiles as strict C99 (this file is built with -std=c99 -pedantic -Werror), and
 * its layout is what the documentation promises: struct_size first, fields in order. */
#include <vobench/vobench_plugin.h>

#include <stdio.h>

#define EXPECT(cond)                                                           \
    do {                                                                       \
        if (!(cond)) {                                                         \
            fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
            return 1;                                                          \
        }                                                                      \
    } while (0)

int main(void) {
    vobench_pose pose = {sizeof(vobench_pose), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
    vobench_camera camera = {0};
    EXPECT(offsetof(vobench_plugin_descriptor, struct_size) == 0);
    EXPECT(offsetof(vobench_dataset_api, struct_size) == 0);
    EXPECT(offsetof(vobench_odometry_api, struct_size) == 0);
    EXPECT(offsetof(vobench_frame, struct_size) == 0);
    EXPECT(offsetof(vobench_image, struct_size) == 0);
    EXPECT(offsetof(vobench_host_services, struct_size) == 0);
    EXPECT(offsetof(vobench_sequence_info, struct_size) == 0);
    EXPECT(offsetof(vobench_param_desc, struct_size) == 0);
    EXPECT(VOBENCH_HAS_FIELD(&pose, vobench_pose, qw));
    pose.struct_size = (uint32_t)offsetof(vobench_pose, qx);
    EXPECT(!VOBENCH_HAS_FIELD(&pose, vobench_pose, qw));
    EXPECT(sizeof camera.distortion / sizeof camera.distortion[0] == 8);
    EXPECT(sizeof(vobench_status) == 4 && sizeof(vobench_plugin_kind) == 4);
    printf("vobench_plugin.h: C99 ok (descriptor %u bytes)\n", (unsigned)sizeof(vobench_plugin_descriptor));
    return 0;
}
