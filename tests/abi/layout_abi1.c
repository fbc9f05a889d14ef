/*
 * layout_abi1.c — the ABI manifest: the size and the offset of every field of every public struct of
 * vobench_plugin.h, as of plugin ABI 1 / API 3 on LP64 (x86_64, aarch64). A reordered, resized or
 * inserted field fails this file's compilation; a field appended at the end (the ABI's only allowed
 * change, rule 2) adds a line here and changes only that struct's size. The role CPython's
 * Misc/stable_abi.toml plays for Python's stable ABI.
 */
#include <vobench/vobench_plugin.h>

#include <stddef.h>

#if defined(__LP64__)
#define PIN_SIZE(s, n) _Static_assert(sizeof(s) == (n), "size of " #s " changed: the ABI broke")
#define PIN(s, f, n) _Static_assert(offsetof(s, f) == (n), "offset of " #s "." #f " changed: the ABI broke")

PIN_SIZE(vobench_param_desc, 64);
PIN(vobench_param_desc, struct_size, 0);
PIN(vobench_param_desc, name, 8);
PIN(vobench_param_desc, type, 16);
PIN(vobench_param_desc, default_value, 24);
PIN(vobench_param_desc, min_value, 32);
PIN(vobench_param_desc, max_value, 40);
PIN(vobench_param_desc, choices, 48);
PIN(vobench_param_desc, help, 56);

PIN_SIZE(vobench_plugin_descriptor, 96);
PIN(vobench_plugin_descriptor, struct_size, 0);
PIN(vobench_plugin_descriptor, abi_version, 4);
PIN(vobench_plugin_descriptor, api_version, 8);
PIN(vobench_plugin_descriptor, kind, 12);
PIN(vobench_plugin_descriptor, name, 16);
PIN(vobench_plugin_descriptor, version, 24);
PIN(vobench_plugin_descriptor, description, 32);
PIN(vobench_plugin_descriptor, license, 40);
PIN(vobench_plugin_descriptor, url, 48);
PIN(vobench_plugin_descriptor, param_count, 56);
PIN(vobench_plugin_descriptor, params, 64);
PIN(vobench_plugin_descriptor, dataset, 72);
PIN(vobench_plugin_descriptor, odometry, 80);
PIN(vobench_plugin_descriptor, filter, 88); /* API 3 */

PIN_SIZE(vobench_host_services, 56);
PIN(vobench_host_services, struct_size, 0);
PIN(vobench_host_services, context, 8);
PIN(vobench_host_services, log, 16);
PIN(vobench_host_services, stage_begin, 24);
PIN(vobench_host_services, stage_end, 32);
PIN(vobench_host_services, counter, 40);
PIN(vobench_host_services, is_cancelled, 48);

PIN_SIZE(vobench_image, 32);
PIN(vobench_image, struct_size, 0);
PIN(vobench_image, width, 4);
PIN(vobench_image, height, 8);
PIN(vobench_image, stride_bytes, 12);
PIN(vobench_image, format, 16);
PIN(vobench_image, data, 24);

PIN_SIZE(vobench_frame, 56);
PIN(vobench_frame, struct_size, 0);
PIN(vobench_frame, index, 8);
PIN(vobench_frame, timestamp, 16);
PIN(vobench_frame, depth_timestamp, 24);
PIN(vobench_frame, color, 32);
PIN(vobench_frame, depth, 40);
PIN(vobench_frame, depth_scale, 48);

PIN_SIZE(vobench_camera, 120);
PIN(vobench_camera, struct_size, 0);
PIN(vobench_camera, width, 4);
PIN(vobench_camera, height, 8);
PIN(vobench_camera, fx, 16);
PIN(vobench_camera, fy, 24);
PIN(vobench_camera, cx, 32);
PIN(vobench_camera, cy, 40);
PIN(vobench_camera, distortion_model, 48);
PIN(vobench_camera, distortion_count, 52);
PIN(vobench_camera, distortion, 56);

PIN_SIZE(vobench_pose, 72);
PIN(vobench_pose, struct_size, 0);
PIN(vobench_pose, timestamp, 8);
PIN(vobench_pose, tx, 16);
PIN(vobench_pose, ty, 24);
PIN(vobench_pose, tz, 32);
PIN(vobench_pose, qx, 40);
PIN(vobench_pose, qy, 48);
PIN(vobench_pose, qz, 56);
PIN(vobench_pose, qw, 64);

PIN_SIZE(vobench_params, 24);
PIN(vobench_params, struct_size, 0);
PIN(vobench_params, count, 4);
PIN(vobench_params, keys, 8);
PIN(vobench_params, values, 16);

PIN_SIZE(vobench_sequence_info, 88);
PIN(vobench_sequence_info, struct_size, 0);
PIN(vobench_sequence_info, name, 8);
PIN(vobench_sequence_info, sensor, 16);
PIN(vobench_sequence_info, camera, 24);
PIN(vobench_sequence_info, depth_width, 32);
PIN(vobench_sequence_info, depth_height, 36);
PIN(vobench_sequence_info, depth_scale, 40);
PIN(vobench_sequence_info, frame_count, 48);
PIN(vobench_sequence_info, ground_truth, 56);
PIN(vobench_sequence_info, gt_count, 64);
PIN(vobench_sequence_info, gt_position_sigma_m, 72);
PIN(vobench_sequence_info, gt_rotation_sigma_deg, 80);

PIN_SIZE(vobench_dataset_api, 64);
PIN(vobench_dataset_api, struct_size, 0);
PIN(vobench_dataset_api, create, 8);
PIN(vobench_dataset_api, open, 16);
PIN(vobench_dataset_api, describe, 24);
PIN(vobench_dataset_api, read_frame, 32);
PIN(vobench_dataset_api, last_error, 40);
PIN(vobench_dataset_api, destroy, 48);
PIN(vobench_dataset_api, extra_params, 56); /* API 3 */

PIN_SIZE(vobench_odometry_config, 32);
PIN(vobench_odometry_config, struct_size, 0);
PIN(vobench_odometry_config, camera, 8);
PIN(vobench_odometry_config, params, 16);
PIN(vobench_odometry_config, seed, 24);

PIN_SIZE(vobench_odometry_api, 64);
PIN(vobench_odometry_api, struct_size, 0);
PIN(vobench_odometry_api, create, 8);
PIN(vobench_odometry_api, start, 16);
PIN(vobench_odometry_api, process, 24);
PIN(vobench_odometry_api, reset, 32);
PIN(vobench_odometry_api, last_error, 40);
PIN(vobench_odometry_api, destroy, 48);
PIN(vobench_odometry_api, extra_params, 56); /* API 3 */

/* API 3 */
PIN_SIZE(vobench_filter_config, 40);
PIN(vobench_filter_config, struct_size, 0);
PIN(vobench_filter_config, camera, 8);
PIN(vobench_filter_config, params, 16);
PIN(vobench_filter_config, seed, 24);
PIN(vobench_filter_config, output_camera, 32);

PIN_SIZE(vobench_filter_api, 48);
PIN(vobench_filter_api, struct_size, 0);
PIN(vobench_filter_api, create, 8);
PIN(vobench_filter_api, start, 16);
PIN(vobench_filter_api, apply, 24);
PIN(vobench_filter_api, last_error, 32);
PIN(vobench_filter_api, destroy, 40);
#endif

int main(void) { return 0; }
