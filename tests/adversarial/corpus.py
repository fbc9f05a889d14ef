#!/usr/bin/env python3
"""The adversarial corpus (issue #14): faults in plugins, readers, data files, configs and results
folders, each of which must end as a failed or refused row (or a refusal with file:line:column) with
its reason, while the sweep finishes and its healthy cells stay byte-identical to a sweep without
the faults. Every case is one line of output; the last line is 'N passed, M failed'.

Run by CTest (tests/adversarial/CMakeLists.txt); by hand:
  corpus.py --vobench build/bin/vobench --plugins build/tests/adversarial/plugins --work /tmp/corpus \
            --constant-pose build/plugins/vobench_constant_pose.so --tum build/plugins/vobench_tum.so
"""
import argparse
import csv
import io
import json
import math
import os
import random
import re
import resource
import shutil
import signal
import struct
import subprocess
import sys
import time
import zlib

HOSTILE = "seq'\"\n; system(\"touch PWNED_gp\") `touch PWNED_bt` $(touch PWNED_sh) <script>alert(1)</script> \\input{/etc/passwd} " \
          "\\write18{touch PWNED_tex} =cmd|' /C calc'!A0 \u202eRTL\u202c | * _x_ [l](u)"

passed, failed = 0, 0


def check(name, ok, detail=""):
    global passed, failed
    if ok:
        passed += 1
        print(f"ok    {name}")
    else:
        failed += 1
        print(f"FAIL  {name}: {detail}")
    sys.stdout.flush()


def run(cmd, timeout=600, env=None, **kw):
    e = dict(os.environ)
    if env:
        e.update(env)
    return subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout, env=e, **kw)


def png_of(chunks):
    """A PNG file of (type, body) chunks, each with its length and CRC."""
    return b"\x89PNG\r\n\x1a\n" + b"".join(
        struct.pack(">I", len(body)) + t + body + struct.pack(">I", zlib.crc32(t + body)) for t, body in chunks)


def grey_png(width, height, level=128):
    """An 8-bit single-channel PNG of one grey level."""
    raw = b"".join(b"\x00" + bytes([level]) * width for _ in range(height))
    return png_of([(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)), (b"IDAT", zlib.compress(raw)), (b"IEND", b"")])


def depth_png(width, height, value):
    """A 16-bit single-channel PNG whose pixel (u, v) holds value(u, v) (TUM depth units)."""
    raw = b"".join(b"\x00" + b"".join(struct.pack(">H", value(u, v)) for u in range(width)) for v in range(height))
    return png_of([(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, 0, 0, 0, 0)), (b"IDAT", zlib.compress(raw)), (b"IEND", b"")])


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def load_json(path):
    with open(path, encoding="utf-8") as f:  # strict: invalid UTF-8 would raise here
        return json.load(f)


def runs_by_algorithm(out):
    """{(dataset, algorithm): run.json} of every finished cell."""
    found = {}
    for cell in os.listdir(os.path.join(out, "runs")):
        p = os.path.join(out, "runs", cell, "run.json")
        if os.path.exists(p):
            r = load_json(p)
            found[(r["cell"]["dataset"], r["cell"]["algorithm"])] = r
    return found


def cell_processes():
    """pids of processes that still carry a cell's tag (none may outlive its cell)."""
    left = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/environ", "rb") as f:
                if b"VOBENCH_CELL_TAG=" in f.read():
                    left.append(int(pid))
        except OSError:
            pass
    return left


def config(path, name, out, datasets, algorithms, extra=""):
    text = f"name: {json.dumps(name)}\noutput: {json.dumps(out)}\nlimits: {{timeout: 5, memory_mb: 512}}\n{extra}datasets:\n"
    for d in datasets:
        text += "  - " + json.dumps(d) + "\n"
    text += "algorithms:\n"
    for a in algorithms:
        text += "  - " + json.dumps(a) + "\n"
    write(path, text)
    return path


def sweep(args, cfg, jobs=2, extra=()):
    t0 = time.time()
    r = run([args.vobench, "run", cfg, "-j", str(jobs), *extra])
    return r, time.time() - t0


def same_healthy(name, faulty_out, clean_out):
    """The healthy cells of a sweep with faults equal those of a sweep without: trajectory bytes, metrics."""
    clean = runs_by_algorithm(clean_out)
    faulty = runs_by_algorithm(faulty_out)
    for key, c in clean.items():
        f = faulty.get(key)
        if f is None:
            check(f"{name}: healthy cell {key} present", False, "missing in the faulty sweep")
            continue
        ta = open(os.path.join(clean_out, "runs", c["cell"]["id"], "trajectory.txt"), "rb").read()
        tb = open(os.path.join(faulty_out, "runs", f["cell"]["id"], "trajectory.txt"), "rb").read()
        check(f"{name}: healthy cell {key[0]}/{key[1]} byte-identical (trajectory, metrics, id)",
              ta == tb and c["metrics"] == f["metrics"] and c["cell"]["id"] == f["cell"]["id"] and f["status"] == "ok",
              f"status {f['status']} {f['reason']}")


def expect_rows(name, out, expected, dataset_key=False):
    found = runs_by_algorithm(out)
    for key, pattern in expected.items():
        r = next((v for k, v in found.items() if (k[0] if dataset_key else k[1]) == key), None)
        if r is None:
            check(f"{name}: {key}", False, "no row")
            continue
        if pattern == "ok":
            check(f"{name}: {key} is a healthy row", r["status"] == "ok", r["reason"])
        else:
            ok = r["status"] == "failed" and re.search(pattern, r["reason"], re.S) is not None and r["metrics"] == {}
            check(f"{name}: {key} -> failed row '{r['reason'][:110]}'", ok, f"status {r['status']}, reason {r['reason']!r}, wanted /{pattern}/")


# ----- plugins: one fault each, healthy reader -------------------------------------------------------

VO_FAULTS = {
    "healthy": "ok",
    "ctor_stdout": "ok",
    "bad_utf8_strings": "ok",
    "entry_crash": r"refused to load: .*killed by signal 11 \(SIGSEGV\)",
    "entry_hang": r"refused to load: .*did not finish within 3 s",
    "close_fds": r"frame stream could not be written at frame 10",
    "huge_pose": r"the metric \S+ is (inf|nan)",
    "nan_counter": r"non-finite value nan for counter 'inliers' at frame 3",
    "many_counters": r"257 counter names in one call .* at frame 3",
    "long_counter_name": r"named a counter with 4096 bytes .* at frame 3",
    "fork_child": r"left 1 process running after the cell ended",
    "fork_escape": r"left 1 process running after the cell ended",
    "kill_parent": r"sent SIGTERM to the harness at frame 3",
    "exit0": r"exited 0 at frame 3 without writing its result",
    "bad_quaternion": r"quaternion of norm 2 \(not unit\) at frame 3",
    "null_last_error": r"failed at frame 3 \(error\): no message",
    "bad_utf8_error": "failed at frame 3 \\(error\\): bad \ufffd",
    "log_flood": r"wrote more than the log limit of 64 MB to stdout/stderr( \(killed\))? at frame \d+",
    "fork_memory": r"exceeded the memory limit of 512 MB \(killed\) at frame 3",
    "unknown_status": r"unknown tracking status 7 at frame 3",
    "create_null": r"create\(\) returned NULL",
    "start_error": r"start failed \(error\): deliberately refuses to start",
    "forge_stream": r"frame stream is corrupt after frame 3",
    "hang_in_destroy": r"timed out after 5 s \(killed\) at frame 30",
    "abort_in_destroy": r"killed by signal 6 \(SIGABRT\) at frame 30",
    "stack_overflow": r"killed by signal 11 \(SIGSEGV\) at frame 3",
    "raise_sigterm": r"killed by signal 15 \(SIGTERM\) at frame 3",
    "forge_success": r"its reader declared 30 when probed alone",
}

READER_FAULTS = {
    "healthy": "ok",
    "hostile_name": "ok",
    "zero_frames": r"declared no frames",
    "nan_stamp": r"gave frame 5 the stamp nan, not a finite number",
    "nan_ground_truth": r"ground-truth pose 2 .*is not finite",
    "stamps_backwards": r"gave frame 4 the stamp .* not after the previous frame",
    "lies_about_count": r"reading frame 10: .*there is no frame 10",
    "wrong_size": r"read_frame\(3\) returned a bad frame: colour image is 32x24",
    "null_camera": r"describe\(\) gave no sequence info or camera",
    "nan_focal": r"unusable camera",
    "crash_in_read": r"killed by signal 11 \(SIGSEGV\) at frame 5",
    "hang_in_open": r"timed out after 5 s",
    "gt_without_array": r"declares ground truth but gives no array",
    "null_frame_data": r"read_frame\(2\) returned a bad frame: colour image has no data",
}


def open3d_params(args, w):
    """open3d_rgbd's one free-text parameter (iterations per pyramid level): a value it cannot use is a
    failed row naming the parameter, beside a healthy one."""
    if not args.open3d:
        print("skip  open3d: no --open3d plugin given (built without libopen3d-dev?)")
        return
    values = {"healthy": ("3,2", "ok"), "not_a_number": ("20,x,5", r"iterations: '20,x,5' is not a comma-separated list"),
              "zero": ("0", r"iterations: '0' is not"), "empty_item": ("5,,5", r"iterations: '5,,5' is not"),
              "nine_levels": ("1,1,1,1,1,1,1,1,1", r"at most 8 pyramid levels"), "huge": ("99999999999999999999", r"is not")}
    algos = [{"name": k, "plugin": args.open3d, "params": {"iterations": v}} for k, (v, _) in values.items()]
    out = os.path.join(w, "open3d")
    cfg = config(os.path.join(w, "open3d.yaml"), "open3d params", out, [corpus_reader(args, w)], algos, extra="frames: 8\n")
    r, seconds = sweep(args, cfg)
    check(f"open3d: the sweep with {len(values) - 1} unusable iterations values finishes (exit 0, {seconds:.1f} s)", r.returncode == 0,
          r.stderr[-1000:])
    expect_rows("open3d", out, {k: p for k, (_, p) in values.items()})


def put_vo_params(args, w):
    """put_vo's noise-model and tracker parameters (issue #19): a value outside its declared range, not a number or
    not in the enumeration refuses the config before any cell runs, naming file:line:column, plugin and
    parameter; the healthy value runs."""
    values = {"healthy": ({"pixel_noise": "0.25"}, None),
              "pixel_noise_zero": ({"pixel_noise": "0"}, r"parameter 'pixel_noise': '0' is outside"),
              "depth_noise_nan": ({"depth_noise": "nan"}, r"parameter 'depth_noise': 'nan' is not a finite number"),
              "depth_noise_huge": ({"depth_noise": "1e400"}, r"parameter 'depth_noise': '1e400' is not a finite number"),
              "refinement_unknown": ({"refinement": "lm"}, r"parameter 'refinement': 'lm' is not one of umeyama\|noise_model"),
              "interpolation_text": ({"depth_interpolation": "sometimes"}, r"parameter 'depth_interpolation'"),
              "field_negative": ({"depth_field": "-1.5"}, r"parameter 'depth_field': '-1.5' is outside"),
              "focal_baseline_zero": ({"focal_baseline": "0"}, r"parameter 'focal_baseline': '0' is outside"),
              "field_off": ({"depth_field": "0"}, None),
              "readout_negative": ({"rolling_shutter_ms": "-20"}, r"parameter 'rolling_shutter_ms': '-20' is outside"),
              "readout_text": ({"rolling_shutter_ms": "fast"}, r"parameter 'rolling_shutter_ms': 'fast' is not"),
              "readout_off": ({"rolling_shutter_ms": "0"}, None),
              "lk_unknown": ({"lk_implementation": "cuda"}, r"parameter 'lk_implementation': 'cuda' is not one of own\|integer\|opencv"),
              "lk_opencv": ({"lk_implementation": "opencv"}, None),
              "lk_own": ({"lk_implementation": "own"}, None),
              "lk_even_window": ({"lk_window": "4"}, None),
              "lk_wide_window": ({"lk_window": "9"}, None),
              "profile_refresh": ({"profile": "refresh"}, None),
              "profile_keyframes": ({"profile": "keyframes"}, None),
              "profile_paper_given_wins": ({"profile": "paper", "lk_flow_prior": "true", "detector": "fast_harris"}, None),
              "profile_unknown": ({"profile": "parallax"}, r"parameter 'profile': 'parallax' is not one of default\|keyframes\|paper\|refresh"),
              "detector_orb": ({"detector": "orb"}, None),
              "detector_fast_harris_deep_pyramid": ({"lk_levels": "8", "lk_window": "61"}, None),
              "detector_unknown": ({"detector": "sift"}, r"parameter 'detector': 'sift' is not one of orb\|fast_harris"),
              "parallax_negative": ({"keyframe_parallax": "-10"}, r"parameter 'keyframe_parallax': '-10' is outside"),
              "parallax_nan": ({"keyframe_parallax": "nan"}, r"parameter 'keyframe_parallax': 'nan' is not a finite number"),
              "refill_not_bool": ({"refill": "-2"}, r"parameter 'refill': '-2' is not a boolean"),
              "refill_off": ({"refill": "false", "keyframe_parallax": "0"}, None),
              "gate_fallback_off": ({"gate_fallback": "false"}, None),
              "gate_fallback_not_bool": ({"gate_fallback": "2"}, r"parameter 'gate_fallback': '2' is not a boolean")}
    for name, (params, pattern) in values.items():
        out = os.path.join(w, "put_vo_params_" + name)
        path = os.path.join(w, f"put_vo_params_{name}.yaml")
        cfg = config(path, "put_vo params", out, [corpus_reader(args, w)], [{"name": name, "plugin": "put_vo", "params": params}],
                     extra="frames: 8\n")
        r, _ = sweep(args, cfg)
        if pattern is None:
            check(f"put_vo: the healthy noise-model parameters run ({name})", r.returncode == 0, r.stderr[-500:])
        else:
            ok = r.returncode != 0 and re.search(re.escape(path) + r":\d+:\d+: plugin 'put_vo', " + pattern, r.stderr) is not None
            check(f"put_vo: {name} refuses the config naming file:line:column and the parameter", ok,
                  f"rc {r.returncode}: {r.stderr[-400:]}")

def synth_inputs(args, w):
    """`vobench synth`'s new inputs (issue #15): a camera file, a stamps folder, an effects list, and
    `synth stats` on folders that are broken. Each is refused with a message naming the file (and
    line) or the option, exit code 1, and nothing half-written is left as a sequence."""
    d = os.path.join(w, "synth_inputs")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    gt = os.path.join(d, "gt.txt")
    write(gt, "".join(f"{100 + 0.1 * k:.1f} {0.01 * k} 0 1.5 0 0 0 1\n" for k in range(10)))

    def refused(name, cmd, pattern):
        r = run([args.vobench] + cmd, timeout=120)
        ok = r.returncode == 1 and re.search(pattern, r.stderr) is not None
        check(f"synth: {name} is refused naming its cause", ok, f"rc {r.returncode}: {r.stderr[-500:]}")

    cams = {"five_numbers": "640 480 500 500 320\n", "zero_focal": "640 480 0 500 320 240\n", "text": "640 480 a b c d\n",
            "fractional_size": "640.5 480 500 500 320 240\n", "nan": "640 480 nan 500 320 240\n", "huge": "99999 480 500 500 320 240\n",
            "empty": "# only a comment\n"}
    for name, text in cams.items():
        f = os.path.join(d, f"camera_{name}.txt")
        write(f, text)
        refused(f"camera file '{name}'", ["synth", "--camera", f, "--frames", "2", "--out", os.path.join(d, "out")],
                re.escape(f) + r"(:\d+: |' has no camera line)")
    refused("an unknown camera name", ["synth", "--camera", "tum-fr7", "--frames", "2", "--out", os.path.join(d, "out")],
            r"tum-fr7.*neither a camera name")
    refused("an unknown effect", ["synth", "--effects", "-motion_blurr", "--frames", "2", "--out", os.path.join(d, "out")],
            r"unknown effect 'motion_blurr'")
    refused("a misspelt correlated_depth_noise", ["synth", "--effects", "+correlated_depth_nois", "--frames", "2", "--out",
                                                 os.path.join(d, "out")], r"unknown effect 'correlated_depth_nois'.*correlated_depth_noise")
    refused("a misspelt fixed_pattern_noise", ["synth", "--effects", "-fixed_pattern_nois", "--frames", "2", "--out", os.path.join(d, "out")],
            r"unknown effect 'fixed_pattern_nois'.*fixed_pattern_noise")
    refused("a misspelt depth_distortion", ["synth", "--effects", "-depth_distorsion", "--frames", "2", "--out", os.path.join(d, "out")],
            r"unknown effect 'depth_distorsion'.*depth_distortion")
    refused("a misspelt stamp_latency", ["synth", "--effects", "-stamp_latncy", "--frames", "2", "--out", os.path.join(d, "out")],
            r"unknown effect 'stamp_latncy'.*stamp_latency")
    # --stamps: no lists; unsorted list; stamps all outside the trajectory; with a built-in path.
    nolists = os.path.join(d, "stamps_none")
    os.makedirs(nolists)
    unsorted = os.path.join(d, "stamps_unsorted")
    write(os.path.join(unsorted, "rgb.txt"), "100.2 rgb/a.png\n100.1 rgb/b.png\n")
    write(os.path.join(unsorted, "depth.txt"), "100.1 depth/a.png\n")
    outside = os.path.join(d, "stamps_outside")
    write(os.path.join(outside, "rgb.txt"), "5.0 rgb/a.png\n")
    write(os.path.join(outside, "depth.txt"), "5.0 depth/a.png\n")
    tum = ["synth", "--trajectory", gt, "--trajectory-format", "tum", "--out"]
    refused("--stamps without rgb.txt", ["synth", "--trajectory", gt, "--trajectory-format", "tum", "--stamps", nolists, "--out",
                                          os.path.join(d, "o1")], r"rgb\.txt")
    refused("--stamps with an unsorted rgb.txt", tum + [os.path.join(d, "o2"), "--stamps", unsorted], r"rgb\.txt:2")
    refused("--stamps outside the trajectory", tum + [os.path.join(d, "o3"), "--stamps", outside], r"time span")
    refused("--stamps with a built-in trajectory", ["synth", "--stamps", outside, "--out", os.path.join(d, "o4")],
            r"--stamps needs --layout tum and a trajectory file")
    check("synth: no sequence is left behind by a refused --stamps run",
          not any(os.path.exists(os.path.join(d, o, "rgb.txt")) for o in ("o1", "o2", "o3", "o4")))
    refused("a misspelt stamp_jitter", ["synth", "--effects", "-stamp_jiter", "--frames", "2", "--out", os.path.join(d, "out")],
            r"unknown effect 'stamp_jiter'.*stamp_jitter")
    # --stamps off any regular clock (effect stamp_jitter fits one to each list): a stamp stalled by
    # 15 ms, a 0.4-s pause, intervals at random. The stamps are legal, so each folder is rendered; what
    # does not fit the clock is taken at its stamp, and synth.json says how the fit went.
    def clock_case(name, stamps, expect):
        f = os.path.join(d, "stamps_" + name)
        write(os.path.join(f, "rgb.txt"), "".join(f"{t:.6f} rgb/{k}.png\n" for k, t in enumerate(stamps)))
        write(os.path.join(f, "depth.txt"), "".join(f"{t + 0.004:.6f} depth/{k}.png\n" for k, t in enumerate(stamps)))
        out = os.path.join(d, "clock_" + name)
        r = run([args.vobench] + tum + [out, "--stamps", f, "--frames", "3"], timeout=300)
        meta = json.load(open(os.path.join(out, "synth.json"))) if r.returncode == 0 else {}
        clock = meta.get("camera_clock", {}).get("color", {})
        check(f"synth --stamps with {name.replace('_', ' ')}: rendered, the clock fit recorded ({expect.__doc__})",
              r.returncode == 0 and expect(clock), f"rc {r.returncode}: {r.stderr[-400:]} {clock}")

    def one_off(c):
        """fitted, one stamp off the clock"""
        return c.get("fitted") is True and c.get("off_clock") == 1 and abs(c.get("period_s", 0) - 1 / 30) < 1e-4
    def paused(c):
        """fitted, the pause counted as dropped frames"""
        return c.get("fitted") is True and c.get("off_clock") == 0 and abs(c.get("period_s", 0) - 1 / 30) < 1e-4
    def recorded(c):
        """whatever the fit found, recorded"""
        return isinstance(c.get("fitted"), bool) and c.get("period_s", -1) >= 0 and c.get("off_clock", -1) >= 0
    clock_case("a_stalled_stamp", [100.0 + k / 30 + (0.015 if k == 12 else 0) for k in range(25)], one_off)
    clock_case("a_pause", [100.0 + k / 30 for k in range(10)] + [100.7 + k / 30 for k in range(6)], paused)
    rng = random.Random(5)
    random_stamps = [100.0]
    while random_stamps[-1] < 100.8:
        random_stamps.append(random_stamps[-1] + rng.uniform(0.010, 0.060))
    clock_case("random_intervals", random_stamps[:-1], recorded)
    # Effect measured_reference reads the trajectory file's noise and smooths the path it renders: a
    # 100-Hz file whose stamps repeat and pause, and one whose quaternions flip sign from line to line
    # (the same rotations: q and −q), must render with finite figures in synth.json, a smoothing that
    # takes away no more than a hundredth of a degree where the file has no noise, and the file's own
    # poses as the reference.
    refused("a misspelt measured_reference", ["synth", "--effects", "-measured_referense", "--frames", "2", "--out",
                                               os.path.join(d, "out")], r"unknown effect 'measured_referense'.*measured_reference")
    def path_case(name, lines, expect):
        f = os.path.join(d, f"path_{name}.txt")
        write(f, "".join(lines))
        out = os.path.join(d, "measured_" + name)
        r = run([args.vobench, "synth", "--trajectory", f, "--trajectory-format", "tum", "--frames", "3", "--out", out], timeout=300)
        meta = json.load(open(os.path.join(out, "synth.json"))).get("measured_reference", {}) if r.returncode == 0 else {}
        numbers = [meta.get("bandwidth_s"), meta.get("residual_rotation_deg"), meta.get("residual_position_m")] + \
            meta.get("noise_rotation_deg", [None]) + meta.get("noise_position_m", [None])
        finite = all(isinstance(x, (int, float)) and math.isfinite(x) for x in numbers)
        first = open(os.path.join(out, "groundtruth.txt")).read().split("\n")[2].split() if r.returncode == 0 else []
        check(f"synth along a file with {name.replace('_', ' ')}: rendered, the smoothing recorded finite ({expect.__doc__})",
              r.returncode == 0 and finite and expect(meta, first), f"rc {r.returncode}: {r.stderr[-400:]} {meta} {first}")

    def kept(meta, first):
        """the file's first pose is the reference"""
        return len(first) == 8 and abs(float(first[1]) - 0.0) < 1e-9
    def untouched(meta, first):
        """no noise read, nothing taken away"""
        return meta.get("residual_rotation_deg", 1) < 0.01 and kept(meta, first)
    noisy = random.Random(9)
    stamps = [100 + 0.01 * k for k in range(80)]
    stamps[20] = stamps[19]
    stamps[40:] = [t + 0.5 for t in stamps[40:]]
    path_case("repeated_and_paused_stamps",
              [f"{t:.4f} {0.002 * k + (noisy.gauss(0, 1e-4) if k else 0):.6f} 0 1.5 "
               f"{noisy.gauss(0, 4e-4):.6f} {noisy.gauss(0, 4e-4):.6f} 0 1\n" for k, t in enumerate(stamps)], kept)
    path_case("quaternion_signs_flipping",
              [f"{100 + 0.01 * k:.4f} {0.002 * k:.6f} 0 1.5 0 {s * math.sin(0.001 * k):.9f} 0 {s * math.cos(0.001 * k):.9f}\n"
               for k, s in ((k, 1 if k % 2 == 0 else -1) for k in range(80))], untouched)
    # synth stats on broken folders.
    good = os.path.join(d, "stats_good")
    r = run([args.vobench, "synth", "--frames", "3", "--layout", "tum", "--out", good], timeout=300)
    check("synth: render a 3-frame folder for the stats cases", r.returncode == 0, r.stderr[-500:])
    r = run([args.vobench, "synth", "stats", good, "--json"], timeout=120)
    check("synth stats: a healthy folder gives one JSON object per folder", r.returncode == 0 and json.loads(r.stdout)[0]["frames"] == 3,
          r.stderr[-500:])

    def broken(name, mutate, pattern):
        b = os.path.join(d, "stats_" + name)
        shutil.copytree(good, b)
        mutate(b)
        refused(f"stats on a folder with {name.replace('_', ' ')}", ["synth", "stats", b], pattern)

    def first_depth(b):
        return os.path.join(b, [l for l in open(os.path.join(b, "depth.txt")) if not l.startswith("#")][0].split()[1])

    def first_rgb(b):
        return os.path.join(b, [l for l in open(os.path.join(b, "rgb.txt")) if not l.startswith("#")][0].split()[1])

    broken("no depth list", lambda b: os.remove(os.path.join(b, "depth.txt")), r"depth\.txt")
    broken("a corrupt colour image", lambda b: write(first_rgb(b), "not a png"), r"cannot be decoded")
    broken("an 8-bit depth image", lambda b: shutil.copy(first_rgb(b), first_depth(b)), r"not a 16-bit single-channel PNG")
    broken("a missing depth image", lambda b: os.remove(first_depth(b)), r"not a 16-bit single-channel PNG")
    broken("a hostile list line", lambda b: write(os.path.join(b, "rgb.txt"), HOSTILE + "\n"), r"rgb\.txt:1")

    def insert_unpaired(b, stream, content):
        """Lists stream/unpaired.png (rgb or depth) between the first two frames, 16.5 ms after the first,
        where no image of the other stream goes with it, and writes `content` (bytes) there."""
        lines = open(os.path.join(b, stream + ".txt")).read().splitlines(keepends=True)
        first = next(i for i, l in enumerate(lines) if not l.startswith("#"))
        stamp = float(lines[first].split()[0]) + 0.0165
        lines.insert(first + 1, f"{stamp:.6f} {stream}/unpaired.png\n")
        write(os.path.join(b, stream + ".txt"), "".join(lines))
        with open(os.path.join(b, stream, "unpaired.png"), "wb") as f:
            f.write(content)

    # The brightness change into the second frame is measured from an unpaired colour image, so it is
    # read and must decode; the noise persistence (depth_noise_persistence.hpp) compares every depth
    # image with the next, so an unpaired one must have the others' size.
    broken("a corrupt unpaired colour image between two frames", lambda b: insert_unpaired(b, "rgb", b"not a png"),
           r"unpaired\.png: cannot be decoded")
    broken("an unpaired depth image of another size between two frames",
           lambda b: insert_unpaired(b, "depth", depth_png(160, 120, lambda u, v: 7500)),
           r"unpaired\.png: not the size of the folder's first depth image")
    # A folder whose name holds the table's own separator: every row of the Markdown table keeps its
    # three cells (labels such as "|Δt|" hold it too).
    piped = os.path.join(d, "stats|a`name")
    shutil.copytree(good, piped)
    r = run([args.vobench, "synth", "stats", piped], timeout=120)
    rows = [l for l in r.stdout.splitlines() if l.startswith("|")]
    cells = {len(re.split(r"(?<!\\)\|", l)) for l in rows}
    check("synth stats: a folder named with | and ` keeps every table row at its cells", r.returncode == 0 and len(rows) > 5 and cells == {4},
          f"cells per row {sorted(cells)}; {r.stderr[-300:]}")
    # synth stats --camera (the reference-consistency and ICP-conditioning statistics): the healthy
    # folder gains them; a bad camera, a broken groundtruth.txt or a camera of another size is refused.
    r = run([args.vobench, "synth", "stats", good, "--camera", "putk2-kinect1", "--json"], timeout=120)
    stats = json.loads(r.stdout)[0]["statistics"] if r.returncode == 0 else {}
    check("synth stats --camera: a healthy rendered folder gets the reference and ICP statistics",
          stats.get("reference.depth_residual_pct.gap_1") is not None and stats.get("geometry.icp_condition") is not None,
          r.stderr[-500:])
    refused("stats with an unknown --camera", ["synth", "stats", good, "--camera", "tum-fr9"], r"tum-fr9.*neither a camera name")
    small = os.path.join(d, "camera_small.txt")
    write(small, "320 240 260 260 160 120\n")
    refused("stats with a --camera of another image size", ["synth", "stats", good, "--camera", small], r"depth is 640×480, the camera's image 320×240")
    gt_cases = {"nan_pose": "1.0 nan 0 0 0 0 0 1\n", "text": "1.0 a b c d e f g\n", "short_line": "1.0 0 0 0 0 0 1\n"}
    for name, text in gt_cases.items():
        b = os.path.join(d, "stats_gt_" + name)
        shutil.copytree(good, b)
        write(os.path.join(b, "groundtruth.txt"), text)
        refused(f"stats --camera on a folder whose groundtruth.txt has a {name.replace('_', ' ')}",
                ["synth", "stats", b, "--camera", "putk2-kinect1"], re.escape(os.path.join(b, "groundtruth.txt")) + r":1")
    # The projector-shadow statistics on depth that has no steps at all (every pixel a hole) and on depth
    # that is nothing but steps (a comb of 1-px columns at 1 m and 2 m with 1-px holes): the first leaves
    # them out (null, no made-up share), the second gives shares within [0, 1] and finite widths.
    for name, value in {"all_holes": lambda u, v: 0, "comb": lambda u, v: (0, 5000, 0, 10000)[u % 4]}.items():
        b = os.path.join(d, "stats_shadow_" + name)
        shutil.copytree(good, b)
        for line in open(os.path.join(b, "depth.txt")):
            if not line.startswith("#"):
                open(os.path.join(b, line.split()[1]), "wb").write(depth_png(640, 480, value))
        r = run([args.vobench, "synth", "stats", b, "--camera", "putk2-kinect1", "--json"], timeout=120)
        stats = json.loads(r.stdout)[0]["statistics"] if r.returncode == 0 else {}
        share, width = stats.get("shadow.no_hole_4_16px"), stats.get("shadow.hole_8_40px")
        ok = share is None and width is None if name == "all_holes" else (
            share is not None and 0 <= share <= 1 and width is not None and math.isfinite(width))
        check(f"synth stats --camera: projector-shadow statistics on depth that is {name.replace('_', ' ')}", r.returncode == 0 and ok,
              r.stderr[-500:] + f" share {share} width {width}")
    # A reference that covers none of the frames: the statistics that need it are left out (no made-up
    # latency or residual), the rest are measured. (10 frames: the latency scan needs pairs 4 frames
    # apart whose stamps the reference covers 40 ms before and 10 ms after; the healthy folder has it.)
    ten = os.path.join(d, "stats_ten")
    r = run([args.vobench, "synth", "--frames", "10", "--layout", "tum", "--out", ten], timeout=300)
    r = run([args.vobench, "synth", "stats", ten, "--camera", "putk2-kinect1", "--json"], timeout=120)
    stats = json.loads(r.stdout)[0]["statistics"] if r.returncode == 0 else {}
    check("synth stats --camera: a healthy 10-frame folder gets the stamp latencies", "stamps.depth_latency_ms" in stats and
          "stamps.color_latency_ms" in stats, r.stderr[-500:] + str(sorted(stats)))
    # The latency pass reads frames the other statistics skipped (--max-frames): a colour image there of
    # another size than its depth is refused too, naming the depth image.
    b = os.path.join(d, "stats_ten_small_colour")
    shutil.copytree(ten, b)
    pairs = [l.split() for l in open(os.path.join(b, "rgb.txt")) if not l.startswith("#")]
    depths = [l.split() for l in open(os.path.join(b, "depth.txt")) if not l.startswith("#")]
    open(os.path.join(b, pairs[5][1]), "wb").write(grey_png(320, 240))
    refused("stats --camera --max-frames 1 with a later colour image of another size",
            ["synth", "stats", b, "--camera", "putk2-kinect1", "--max-frames", "1"],
            re.escape(os.path.join(b, depths[5][1])) + r": depth is 640×480, colour 320×240 \(not registered\)")
    b = os.path.join(d, "stats_gt_elsewhere")
    shutil.copytree(ten, b)
    write(os.path.join(b, "groundtruth.txt"), "5000.0 0 0 0 0 0 0 1\n5000.1 0 0 0 0 0 0 1\n")
    r = run([args.vobench, "synth", "stats", b, "--camera", "putk2-kinect1", "--json"], timeout=120)
    stats = json.loads(r.stdout)[0]["statistics"] if r.returncode == 0 else {}
    check("synth stats --camera: a groundtruth.txt beside none of the frames leaves out the reference and latency statistics",
          r.returncode == 0 and "geometry.icp_condition" in stats and
          not any(k.startswith("reference.") or k.endswith("_latency_ms") for k in stats), r.stderr[-500:] + str(sorted(stats)))
    # The fixed disparity pattern (disparity_pattern.hpp) is solved from how points move across the
    # image: a still camera's 40 frames (the ten images listed four times, one reference pose) carry no
    # point across it, and a 10-frame folder is too short to tell a pattern from noise — both leave it
    # out (no made-up 0), the rest is measured.
    b = os.path.join(d, "stats_still_camera")
    shutil.copytree(ten, b)
    for stream in ("rgb", "depth"):
        paths = [l.split()[1] for l in open(os.path.join(b, stream + ".txt")) if not l.startswith("#")]
        write(os.path.join(b, stream + ".txt"), "".join(f"{1.0 + k / 30.0:.6f} {paths[k % len(paths)]}\n" for k in range(40)))
    write(os.path.join(b, "groundtruth.txt"), "".join(f"{0.5 + k / 100.0:.2f} 0 0 0 0 0 0 1\n" for k in range(250)))
    for name, folder in {"a still camera's 40 frames": b, "a 10-frame folder": ten}.items():
        r = run([args.vobench, "synth", "stats", folder, "--camera", "putk2-kinect1", "--json"], timeout=300)
        stats = json.loads(r.stdout)[0]["statistics"] if r.returncode == 0 else {}
        check(f"synth stats --camera: {name} leaves out the fixed disparity pattern, keeps the rest",
              r.returncode == 0 and "reference.depth_residual_pct.gap_1" in stats and not any("disparity_pattern" in k for k in stats),
              r.stderr[-500:] + str(sorted(stats)))
    # synth fit-distortion reads the same folders: a broken depth image, groundtruth.txt or --expect is
    # refused naming it; a reference beside none of the frames gives no field (not one of zeros).
    refused("fit-distortion on a folder without depth.txt", ["synth", "fit-distortion", os.path.join(d, "stats_no depth list")], r"depth\.txt")
    refused("fit-distortion on a folder with an 8-bit depth image", ["synth", "fit-distortion", os.path.join(d, "stats_an 8-bit depth image"),
            "--camera", "putk2-kinect1"], r"not a 16-bit single-channel PNG")
    refused("fit-distortion on a folder whose groundtruth.txt has a NaN pose",
            ["synth", "fit-distortion", os.path.join(d, "stats_gt_nan_pose"), "--camera", "putk2-kinect1"],
            re.escape(os.path.join(d, "stats_gt_nan_pose", "groundtruth.txt")) + r":1")
    refused("fit-distortion with a --camera of another image size", ["synth", "fit-distortion", ten, "--camera", small],
            r"depth is 640×480, the camera's image 320×240")
    refused("fit-distortion on a folder whose reference covers no frame pair",
            ["synth", "fit-distortion", os.path.join(d, "stats_gt_elsewhere"), "--camera", "putk2-kinect1"], r"covers no pair")
    refused("fit-distortion with an --expect that is not three numbers",
            ["synth", "fit-distortion", ten, "--camera", "putk2-kinect1", "--expect", "1,2;rm -rf /"], r"not three numbers")
    refused("fit-distortion with a --tolerance that is neither one nor three numbers",
            ["synth", "fit-distortion", ten, "--camera", "putk2-kinect1", "--expect", "0,1,0", "--tolerance", "0.1,0.2"],
            r"--tolerance: '0.1,0.2' is not three numbers")
    refused("fit-distortion with a negative --tolerance",
            ["synth", "fit-distortion", ten, "--camera", "putk2-kinect1", "--expect", "0,1,0", "--tolerance", "-1"], r"negative")
    refused("fit-distortion with a --reference-turn-deg that is not three finite numbers",
            ["synth", "fit-distortion", ten, "--camera", "putk2-kinect1", "--fit-turn", "--reference-turn-deg", "nan,0,0"],
            r"--reference-turn-deg: 'nan,0,0' is not three numbers")
    refused("fit-distortion with a --depth-latency-ms that is not a finite number",
            ["synth", "fit-distortion", ten, "--camera", "putk2-kinect1", "--fit-latency", "--depth-latency-ms", "nan"],
            r"(must be finite|depth-latency-ms)")
    refused("fit-distortion, joint, on a folder whose reference covers no frame pair",
            ["synth", "fit-distortion", os.path.join(d, "stats_gt_elsewhere"), "--camera", "putk2-kinect1", "--fit-latency", "--fit-turn"],
            r"covers no pair")
    # synth undo-distortion writes a corrected copy: never over a folder with contents, never outside
    # its output (a list naming ../ or an absolute path), never with a field that is not three numbers.
    refused("undo-distortion into the folder it reads", ["synth", "undo-distortion", ten, "--out", ten, "--field", "0,1,0"],
            r"not an empty folder")
    refused("undo-distortion with a --field that is not three finite numbers",
            ["synth", "undo-distortion", ten, "--out", os.path.join(d, "undo_nan"), "--field", "0,nan,1"], r"--field: '0,nan,1' is not three numbers")
    refused("undo-distortion with a camera that has no measured field and no --field",
            ["synth", "undo-distortion", ten, "--out", os.path.join(d, "undo_nofield"), "--camera", "putk2-kinect1"], r"no measured disparity")
    b = os.path.join(d, "undo_escape")
    shutil.copytree(ten, b)
    write(os.path.join(b, "depth.txt"), "1.0 ../../../escaped.png\n")
    refused("undo-distortion on a depth.txt naming a path outside the folder",
            ["synth", "undo-distortion", b, "--out", os.path.join(d, "undo_escape_out"), "--field", "0,1,0", "--camera", "putk2-kinect1"],
            r"depth\.txt: entry 1 .*not a path inside")
    check("undo-distortion: a refused list writes nothing", not os.path.exists(os.path.join(d, "undo_escape_out")), "")
    r = run([args.vobench, "synth", "undo-distortion", ten, "--out", os.path.join(d, "undo_ok"), "--field", "0,1,0",
             "--camera", "putk2-kinect1"], timeout=120)
    check("undo-distortion: a healthy folder is copied with every depth image", r.returncode == 0 and
          len(os.listdir(os.path.join(d, "undo_ok", "depth"))) == len(os.listdir(os.path.join(ten, "depth"))), r.stderr[-500:])


def plot_inputs(args, w):
    """`vobench plot`'s inputs (issue #18): trajectory files of any format, legend labels and the figure
    name. A hostile label is drawn as text and runs nothing; a broken file, a figure name that cannot be
    quoted and an estimate that cannot be aligned are refused (exit 1) naming the file or the option."""
    d = os.path.join(w, "plot_inputs")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    gt = os.path.join(d, "gt.txt")
    write(gt, "".join(f"{0.1 * k:.1f} {0.1 * k} {0.02 * k * k} 0 0 0 0 1\n" for k in range(20)))
    est = os.path.join(d, "est.txt")
    write(est, "".join(f"{0.1 * k:.1f} {0.1 * k + 1} {0.02 * k * k} 0.5 0 0 0 1\n" for k in range(20)))
    r = run([args.vobench, "plot", "--ref", gt, est, "--label", HOSTILE, "--out", os.path.join(d, "hostile.png")], cwd=d)
    pwned = [f for dp, _, fs in os.walk(d) for f in fs if f.startswith("PWNED")]
    drawn = os.path.exists(os.path.join(d, "hostile.png"))
    check("plot: a hostile legend label is drawn as text, nothing runs", r.returncode == 0 and drawn and not pwned,
          f"rc {r.returncode} drawn {drawn} pwned {pwned} {r.stderr[-300:]}")
    # The interactive page: the label is a \u-escaped string in the data island and the <title>'s text.
    page = os.path.join(d, "hostile.html")
    r = run([args.vobench, "plot", "--ref", gt, est, "--label", HOSTILE, "--out", page], cwd=d)
    html = open(page, encoding="utf-8").read() if os.path.exists(page) else ""
    island = html.split('id="vobench-data">', 1)[1].split("</script>", 1)[0] if "vobench-data" in html else None
    labels = [t["label"] for t in json.loads(island)["views"][0]["tracks"]] if island else []
    check("plot --out F.html: a hostile label stays text (no markup in the data island, three scripts, the label intact)",
          r.returncode == 0 and island is not None and "<" not in island and html.count("<script>") == 3 and
          any("alert(1)" in l for l in labels) and "<script>alert" not in html, f"rc {r.returncode} {r.stderr[-300:]}")

    def refused(name, cmd, pattern):
        r = run([args.vobench, "plot"] + cmd, timeout=120)
        ok = r.returncode == 1 and re.search(pattern, r.stderr) is not None
        check(f"plot: {name} is refused naming its cause", ok, f"rc {r.returncode}: {r.stderr[-500:]}")

    nan = os.path.join(d, "nan.txt")
    write(nan, "0 0 0 0 0 0 0 1\n0.1 nan 0 0 0 0 0 1\n")
    refused("a trajectory with a NaN", ["--ref", gt, nan, "--out", os.path.join(d, "f.png")], re.escape(nan) + r":2: ")
    binary = os.path.join(d, "binary.txt")
    open(binary, "wb").write(bytes(range(256)) * 16)
    refused("a binary trajectory file", ["--ref", gt, binary, "--out", os.path.join(d, "f.png")], re.escape(binary))
    far = os.path.join(d, "far.txt")
    write(far, "".join(f"{500 + 0.1 * k:.1f} {k} 0 0 0 0 0 1\n" for k in range(5)))
    refused("an estimate with no stamp near the reference's", ["--ref", gt, far, "--out", os.path.join(d, "f.png")],
            r"far\.txt: cannot be aligned to gt\.txt")
    refused("a figure name with quotes and a newline", ["--ref", gt, est, "--out", os.path.join(d, "x'\n`touch PWNED_n`.png")],
            r"plain file name")
    refused("a figure that is not PNG, SVG, PDF or HTML", ["--ref", gt, est, "--out", os.path.join(d, "f.gif")], r"\.png, \.svg, \.pdf or \.html")
    refused("a TUM file read as KITTI (8 numbers a line)", ["--ref", gt, gt, "--format", "kitti", "--out", os.path.join(d, "f.png")],
            re.escape(gt) + r":1: ")


def corpus_plugin(args, kind, fault):
    return os.path.join(args.plugins, f"corpus_{kind}_{fault}.so")


def corpus_reader(args, w):
    """The healthy corpus reader's dataset entry (its sequence is made in memory; the folder only names it)."""
    seq = os.path.join(w, "empty_sequence")
    os.makedirs(seq, exist_ok=True)
    return {"name": "corpus", "reader": corpus_plugin(args, "reader", "healthy"), "path": seq}


def plugin_faults(args, w):
    p = lambda kind, f: corpus_plugin(args, kind, f)
    reader = corpus_reader(args, w)
    healthy = [{"name": "healthy", "plugin": p("vo", "healthy")}, {"name": "constant_pose", "plugin": args.constant_pose}]
    clean = config(os.path.join(w, "vo_clean.yaml"), "vo clean", os.path.join(w, "vo_clean"), [reader], healthy)
    faulty = config(os.path.join(w, "vo_faults.yaml"), "vo faults", os.path.join(w, "vo_faults"), [reader],
                    healthy[1:] + [{"name": f, "plugin": p("vo", f)} for f in VO_FAULTS])
    r0, _ = sweep(args, clean)
    check("plugins: the clean sweep succeeds", r0.returncode == 0, r0.stderr[-2000:])
    r1, seconds = sweep(args, faulty)
    check(f"plugins: the sweep with {len(VO_FAULTS) - 3} plugin faults finishes (exit 0, {seconds:.1f} s)",
          r1.returncode == 0 and "sweep finished" in r1.stderr, f"exit {r1.returncode}: {r1.stderr[-3000:]}")
    expect_rows("plugins", os.path.join(w, "vo_faults"), VO_FAULTS)
    same_healthy("plugins", os.path.join(w, "vo_faults"), os.path.join(w, "vo_clean"))
    check("plugins: no process of any cell outlives it", not cell_processes(), f"left: {cell_processes()}")
    lb = load_json(os.path.join(w, "vo_faults", "leaderboard.json"))
    ranked = [e["entry"] for e in lb["entries"] if e.get("rank") is not None]
    check("plugins: only healthy entries are ranked", set(ranked) <= {"healthy", "ctor_stdout", "bad_utf8_strings", "constant_pose"}, ranked)
    out = r1.stdout
    check("plugins: the constructor's stdout never reaches vobench's output", "not vobench's output" not in out, out[:500])


def reader_faults(args, w):
    p = lambda f: os.path.join(args.plugins, f"corpus_reader_{f}.so")
    seq = os.path.join(w, "empty_sequence")
    vo = [{"name": "vo", "plugin": os.path.join(args.plugins, "corpus_vo_healthy.so")}]
    clean = config(os.path.join(w, "reader_clean.yaml"), "readers clean", os.path.join(w, "reader_clean"),
                   [{"name": "healthy", "reader": p("healthy"), "path": seq}], vo)
    faulty = config(os.path.join(w, "reader_faults.yaml"), "readers", os.path.join(w, "reader_faults"),
                    [{"name": f, "reader": p(f), "path": seq} for f in READER_FAULTS], vo)
    r0, _ = sweep(args, clean)
    check("readers: the clean sweep succeeds", r0.returncode == 0, r0.stderr[-2000:])
    r1, seconds = sweep(args, faulty)
    check(f"readers: the sweep with {len(READER_FAULTS) - 2} reader faults finishes ({seconds:.1f} s)", r1.returncode == 0, r1.stderr[-3000:])
    expect_rows("readers", os.path.join(w, "reader_faults"), READER_FAULTS, dataset_key=True)
    same_healthy("readers", os.path.join(w, "reader_faults"), os.path.join(w, "reader_clean"))
    hostile = next(v for k, v in runs_by_algorithm(os.path.join(w, "reader_faults")).items() if k[0] == "hostile_name")
    traj = open(os.path.join(w, "reader_faults", "runs", hostile["cell"]["id"], "trajectory.txt")).read().splitlines()
    poses = [l for l in traj if l and not l.startswith("#")]
    check("readers: a sequence name with a newline adds no pose line to trajectory.txt", len(poses) == 30, f"{len(poses)} poses")
    check("readers: no process of any cell outlives it", not cell_processes(), f"left: {cell_processes()}")


# ----- data files: the tum reader on broken copies of a rendered sequence ------------------------------

def data_faults(args, w):
    base = os.path.join(w, "tum_good")
    if not os.path.isdir(base):
        r = run([args.vobench, "synth", "--sensor", "kinect1", "--trajectory", "explore1", "--frames", "8", "--seed", "1",
                 "--layout", "tum", "--out", base])
        check("data: render an 8-frame TUM-layout sequence", r.returncode == 0, r.stderr[-1000:])
    root = os.path.join(w, "tum_variants")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)

    def variant(name, mutate):
        d = os.path.join(root, name)
        shutil.copytree(base, d)
        mutate(d)
        return name

    def lines(d, f):
        return open(os.path.join(d, f)).read().splitlines()

    def corrupt_png(d):
        f = os.path.join(d, lines(d, "rgb.txt")[3 + 3].split()[1])
        data = open(f, "rb").read()
        open(f, "wb").write(data[: len(data) // 3])

    def missing_depth(d):
        os.remove(os.path.join(d, lines(d, "depth.txt")[3 + 4].split()[1]))

    def garbage_list(d):
        with open(os.path.join(d, "rgb.txt"), "a") as f:
            f.write("this is not a stamp rgb/x.png\n")

    def nan_gt(d):
        g = lines(d, "groundtruth.txt")
        g[4] = "0.2 nan nan nan 0 0 0 1"
        write(os.path.join(d, "groundtruth.txt"), "\n".join(g) + "\n")

    def binary_gt(d):
        open(os.path.join(d, "groundtruth.txt"), "wb").write(bytes(range(256)) * 64)

    # PNG files that get past the signature, for the readers' own PNG path (plugins/common/png_raster.cpp)
    # and then cv::imread: each is a clear failure naming the frame and file, or decodes as libpng does.
    def png_chunks(b):
        at, out = 8, []
        while at + 12 <= len(b):
            n = struct.unpack(">I", b[at:at + 4])[0]
            out.append((b[at + 4:at + 8], b[at + 8:at + 8 + n]))
            at += 12 + n
        return out

    def frame_file(d, listing, k):
        return os.path.join(d, lines(d, listing)[3 + k].split()[1])

    def png_bad_crc(d):  # one byte of the image data changed, the chunk's CRC left as it was
        f = frame_file(d, "rgb.txt", 2)
        b = bytearray(open(f, "rb").read())
        b[b.find(b"IDAT") + 100] ^= 0x5A
        open(f, "wb").write(bytes(b))

    def png_claims_huge(d):  # a valid header (right CRC) claiming 60000 x 60000 pixels
        f = frame_file(d, "depth.txt", 5)
        chunks = png_chunks(open(f, "rb").read())
        chunks[0] = (b"IHDR", struct.pack(">II", 60000, 60000) + chunks[0][1][8:])
        open(f, "wb").write(png_of(chunks))

    def png_8bit_depth(d):  # a well-formed 8-bit grey PNG where 16-bit depth belongs
        rows = b"".join(b"\x00" + bytes([(x + y) % 256 for x in range(640)]) for y in range(480))
        open(frame_file(d, "depth.txt", 6), "wb").write(
            png_of([(b"IHDR", struct.pack(">IIBBBBB", 640, 480, 8, 0, 0, 0, 0)), (b"IDAT", zlib.compress(rows)), (b"IEND", b"")]))

    def png_too_much_data(d):  # the zlib stream holds one row more than the image (valid CRCs)
        f = frame_file(d, "rgb.txt", 1)
        chunks = png_chunks(open(f, "rb").read())
        raw = zlib.decompress(b"".join(body for t, body in chunks if t == b"IDAT"))
        rest = [c for c in chunks if c[0] not in (b"IDAT", b"IEND")]
        open(f, "wb").write(png_of(rest + [(b"IDAT", zlib.compress(raw + raw[:640 * 3 + 1])), (b"IEND", b"")]))

    expected = {
        "good": "ok",
        variant("corrupt_png", corrupt_png): r"reading frame 3: ",
        variant("png_bad_crc", png_bad_crc): r"reading frame 2: .*rgb.*cannot decode image",
        variant("png_claims_huge", png_claims_huge): r"reading frame 5: .*depth.*cannot decode image",
        variant("png_8bit_depth", png_8bit_depth): r"reading frame 6: .*depth.*16-bit",
        variant("png_too_much_data", png_too_much_data): r"ok|reading frame 1: .*rgb.*cannot decode image",
        variant("missing_depth", missing_depth): r"reading frame 4: |setting up: .*depth",
        variant("garbage_list", garbage_list): r"setting up: .*rgb\.txt",
        variant("nan_ground_truth", nan_gt): r"ok|ground-truth pose .* not finite|groundtruth\.txt",
        variant("binary_ground_truth", binary_gt): r"setting up: .*groundtruth\.txt",
    }
    shutil.copytree(base, os.path.join(root, "good"))
    hostile_dir = HOSTILE.replace("/", "_")
    shutil.copytree(base, os.path.join(root, hostile_dir))
    cp = [{"name": "constant_pose", "plugin": args.constant_pose}]
    clean = config(os.path.join(w, "data_clean.yaml"), "data clean", os.path.join(w, "data_clean"),
                   [{"name": "good", "reader": args.tum, "path": os.path.join(root, "good")}], cp)
    faulty = config(os.path.join(w, "data_faults.yaml"), HOSTILE, os.path.join(w, "data_faults"),
                    [{"name": k, "reader": args.tum, "path": os.path.join(root, k)} for k in expected] +
                    [{"name": HOSTILE, "reader": args.tum, "path": root, "sequences": [hostile_dir]}], cp)
    r0, _ = sweep(args, clean)
    check("data: the clean sweep succeeds", r0.returncode == 0, r0.stderr[-2000:])
    r1, seconds = sweep(args, faulty, extra=())
    check(f"data: the sweep over {len(expected) - 1} broken data folders and a hostile name finishes ({seconds:.1f} s)",
          r1.returncode == 0, r1.stderr[-3000:])
    found = runs_by_algorithm(os.path.join(w, "data_faults"))
    for name, pattern in expected.items():
        r = found.get((name, "constant_pose"))
        if r is None:
            check(f"data: {name}", False, "no row")
        elif pattern == "ok":
            check(f"data: {name} is a healthy row", r["status"] == "ok", r["reason"])
        else:
            ok = (pattern.startswith("ok|") and r["status"] == "ok") or (r["status"] == "failed" and re.search(pattern, r["reason"]))
            check(f"data: {name} -> {r['status']} '{r['reason'][:100]}'", bool(ok), f"wanted /{pattern}/")
    same_healthy("data", os.path.join(w, "data_faults"), os.path.join(w, "data_clean"))
    hostile_outputs(os.path.join(w, "data_faults"), "data (hostile dataset, sweep and folder names)")


def hostile_outputs(out, what):
    """Every output of a report whose names are hostile: parses, and no command ran."""
    pwned = [os.path.join(dp, f) for dp, _, fs in os.walk(os.path.dirname(out)) for f in fs if f.startswith("PWNED")]
    pwned += [f for f in os.listdir(".") if f.startswith("PWNED")]
    check(f"{what}: no command ran (gnuplot system, backticks, $(…), \\write18)", not pwned, pwned)
    md = open(os.path.join(out, "summary.md"), encoding="utf-8").read()
    rows = [l for l in md.splitlines() if l.startswith("|")]
    bad_rows = [l for l in rows if (len(re.findall(r"(?<!\\)\|", l)) != len(re.findall(r"(?<!\\)\|", rows[0])) and "---" not in l and
                                    not l.startswith("| cell") and not l.startswith("| sequence"))]
    check(f"{what}: summary.md has no raw newline, <script> or unescaped | in a name", "<script>" not in md and "\n; system" not in md,
          md[:300])
    with open(os.path.join(out, "summary.csv"), encoding="utf-8", newline="") as f:
        table = list(csv.reader(f))
    check(f"{what}: summary.csv parses to rows of equal width, no cell a formula",
          len({len(r) for r in table}) == 1 and not any(c[:1] in "=+@" for r in table[1:] for c in r if c and not re.match(r"^[-+]?[0-9.eE+-]+$", c)),
          [len(r) for r in table])
    tex = open(os.path.join(out, "summary.tex"), encoding="utf-8").read()
    allowed = {"begin", "end", "centering", "caption", "toprule", "midrule", "bottomrule", "multicolumn", "textbackslash", "textasciitilde",
               "textasciicircum", "textless", "textgreater", "textbar", "textquotedbl", "pm", "dagger", "ddagger", "circ", "usepackage",
               "Delta", "textbf"}
    body = "\n".join(l for l in tex.splitlines() if not l.startswith("%"))
    commands = set(re.findall(r"\\([a-zA-Z]+)", body))  # comment lines may carry any text
    check(f"{what}: summary.tex runs no command but its own (\\input and \\write18 escaped)",
          commands <= allowed and all("\n" not in l for l in tex.splitlines()), commands - allowed)
    html = open(os.path.join(out, "report.html"), encoding="utf-8").read()
    # The page's own four scripts (CSP listener, table sorting, plotly.js, the explorer) and its data island; a
    # name is text in the tables and a \u-escaped JSON string in the island, never markup.
    island = html.split('<script type="application/json" id="vobench-data">', 1)[1].split("</script>", 1)[0] if "vobench-data" in html else None
    check(f"{what}: report.html carries the names as text only", html.count("<script>") == 4 and "alert(1)</script>" not in html and
          "\u202e" not in html and island is not None and "<" not in island and ">" not in island, "a <script> or a bidi override from a name")
    load_json(os.path.join(out, "leaderboard.json"))
    check(f"{what}: leaderboard.json is valid UTF-8 JSON", True)
    figs = os.path.join(out, "figures")
    if shutil.which("gnuplot"):
        logs = [f for f in os.listdir(figs) if f.endswith(".log")]
        pngs = [f for f in os.listdir(figs) if f.endswith(".png")]
        check(f"{what}: gnuplot drew every figure ({len(pngs)} PNG, no error log)", pngs and not logs, logs)
    stems = [f[:-3] for f in os.listdir(figs) if f.endswith(".gp")]
    check(f"{what}: figure names are slugs with a hash", all(re.match(r"^[a-z0-9._-]+-[0-9a-f]{8}$", s) for s in stems), stems)


# ----- configs -----------------------------------------------------------------------------------------

def config_faults(args, w):
    d = os.path.join(w, "configs")
    os.makedirs(d, exist_ok=True)
    bomb = 'a: &a ["x","x","x","x","x","x","x","x","x"]\n'
    for p_, q in zip("abcdefgh", "bcdefghi"):
        bomb += f"{q}: &{q} [*{p_},*{p_},*{p_},*{p_},*{p_},*{p_},*{p_},*{p_},*{p_}]\n"
    cases = {
        "alias bomb": (bomb, r"bomb\.yaml:\d+:\d+: the configuration expands to more than 100000 nodes"),
        "duplicate key": ("name: a\noutput: b\nname: c\n", r"duplicate_key\.yaml:3:1: the key 'name' is given twice"),
        "nested duplicate key": ("datasets:\n  - {name: a, name: b}\n", r"nested_duplicate_key\.yaml:2:\d+: the key 'name' is given twice"),
        "2 MB config": ("# " + "x" * (2 << 20) + "\n", r"larger than 1048576 bytes"),
        "deep nesting": ("a: " + "[" * 100000 + "]" * 100000 + "\n", r"nested too deeply"),
        "binary garbage": (bytes(range(1, 256)).decode("latin-1") * 10, r"\.yaml:\d+:\d+: "),
        "unknown key": ("name: a\nbogus: 1\n", r"unknown_key\.yaml:2:1: unknown key 'bogus'"),
        "wrong type": ("name: a\nrepeats: [1, 2]\ndatasets: []\n", r"wrong_type\.yaml:2:\d+: "),
    }
    for name, (text, pattern) in cases.items():
        f = os.path.join(d, name.replace(" ", "_").replace("2_MB", "big") + ".yaml")
        with open(f, "w", encoding="latin-1") as fh:
            fh.write(text)
        t0 = time.time()
        r = run(["/usr/bin/time", "-f", "peak %M KB", args.vobench, "run", f, "--dry-run"])
        peak = re.search(r"peak (\d+) KB", r.stderr)
        peak_kb = int(peak.group(1)) if peak else 0
        ok = r.returncode != 0 and re.search(pattern, r.stderr) is not None and peak_kb < 200 * 1024
        check(f"configs: {name} refused with file:line:column ({peak_kb // 1024} MB, {time.time() - t0:.2f} s)", ok,
              f"exit {r.returncode}: {r.stderr[-400:]}")


# ----- results folders -----------------------------------------------------------------------------------

def results_faults(args, w):
    src = os.path.join(w, "vo_clean")
    cfg = os.path.join(w, "vo_clean.yaml")
    ids = sorted(i for i in os.listdir(os.path.join(src, "runs")) if not i.startswith("."))

    def fresh(name):
        d = os.path.join(w, "results", name)
        shutil.rmtree(d, ignore_errors=True)
        shutil.copytree(src, d, ignore=shutil.ignore_patterns(".vobench.lock"))
        return d

    def report(d):
        return run([args.vobench, "report", d])

    def run_json(d, i):
        return os.path.join(d, "runs", i, "run.json")

    # A truncated run.json: listed by the report (exit 2), re-run by --resume, then identical.
    d = fresh("truncated")
    text = open(run_json(d, ids[0])).read()
    write(run_json(d, ids[0]), text[: len(text) // 2])
    r = report(d)
    check("results: a truncated run.json is listed and the report exits 2", r.returncode == 2 and ids[0] in r.stdout and "INCOMPLETE" in r.stdout,
          f"exit {r.returncode}: {r.stdout[-500:]}")
    r = run([args.vobench, "run", cfg, "--out", d, "--resume"])
    again = load_json(run_json(d, ids[0]))
    check("results: --resume runs the corrupt cell again; then complete and identical", r.returncode == 0 and again["metrics"] == load_json(run_json(src, ids[0]))["metrics"]
          and os.path.isdir(os.path.join(d, "corrupt")), f"exit {r.returncode}: {r.stderr[-800:]}")

    # Hostile strings inside a record reach every writer.
    d = fresh("hostile_record")
    j = load_json(run_json(d, ids[0]))
    j["cell"]["sequence"] = HOSTILE
    j["cell"]["algorithm"] = HOSTILE
    j["reason"] = HOSTILE
    write(run_json(d, ids[0]), json.dumps(j))
    cwd = os.getcwd()
    os.chdir(d)
    r = report(d)
    os.chdir(cwd)
    check("results: a record with hostile names is reported (exit 0)", r.returncode == 0, r.stderr[-800:])
    hostile_outputs(d, "results (hostile names in run.json)")

    # Stored metrics that do not match the trajectory.
    d = fresh("tampered")
    j = load_json(run_json(d, ids[0]))
    j["metrics"]["ate.rmse"] += 0.01  # a clear change whatever the true value (the healthy cell's is 0)
    write(run_json(d, ids[0]), json.dumps(j))
    r = report(d)
    check("results: a tampered metric (+1 cm) is caught ('run.json says …, its trajectory gives …', exit 2)",
          r.returncode == 2 and "run.json says ate.rmse" in r.stdout, r.stdout[-600:])

    r = run([args.vobench, "report", "--re-evaluate", d])
    cells = {c["id"]: c for e in load_json(os.path.join(d, "leaderboard.json"))["entries"] for c in e["cells"]}
    truth = load_json(run_json(src, ids[0]))["metrics"]["ate.rmse"]
    check("results: `report --re-evaluate` recomputes every cell and reports the trajectory's value (exit 0)",
          r.returncode == 0 and abs(cells[ids[0]]["metrics"]["ate.rmse"] - truth) < 1e-12, f"exit {r.returncode}: {r.stdout[-400:]}")

    d = fresh("short_trajectory")
    t = os.path.join(d, "runs", ids[0], "trajectory.txt")
    lines = open(t).read().splitlines()
    write(t, "\n".join(lines[:-5]) + "\n")
    r = report(d)
    check("results: a trajectory shorter than its record is caught (exit 2)", r.returncode == 2 and "poses, run.json says" in r.stdout, r.stdout[-600:])

    # Real-time records: a forged dropped_frames count cannot hide missing poses, nor exceed the frames.
    for name, dropped, want in (("dropped_hides_poses", 5, "poses, run.json says"), ("dropped_too_many", 10**6, "more frames were dropped")):
        d = fresh(name)
        j = load_json(run_json(d, ids[0]))
        j["dropped_frames"] = dropped
        write(run_json(d, ids[0]), json.dumps(j))
        r = report(d)
        check(f"results: run.json with dropped_frames = {dropped} and every pose is caught (exit 2)", r.returncode == 2 and want in r.stdout,
              r.stdout[-600:])

    d = fresh("missing_cell")
    shutil.rmtree(os.path.join(d, "runs", ids[0]))
    r = report(d)
    check("results: a cell of cells.json without a record is listed as missing (exit 2)", r.returncode == 2 and "missing" in r.stdout, r.stdout[-600:])

    d = fresh("schema")
    j = load_json(run_json(d, ids[0]))
    j["schema_version"] = 99
    write(run_json(d, ids[0]), json.dumps(j))
    r = report(d)
    check("results: an unknown schema_version is refused (exit 2)", r.returncode == 2 and "schema_version" in r.stdout, r.stdout[-600:])

    d = fresh("wrong_id")
    os.rename(os.path.join(d, "runs", ids[0]), os.path.join(d, "runs", "0000000000000000"))
    r = report(d)
    check("results: a record in another cell's folder is refused (exit 2)", r.returncode == 2 and "does not describe cell" in r.stdout, r.stdout[-600:])

    d = fresh("bad_sweep_json")
    write(os.path.join(d, "sweep.json"), json.dumps({"name": 7, "rank_by": "no.such", "criteria": [{"criterion": "$(rm -rf /)"}]}))
    r = report(d)
    check("results: a sweep.json of wrong types makes the report use its defaults (exit 0, warned)", r.returncode == 0 and "defaults" in r.stderr,
          f"exit {r.returncode}: {r.stderr[-500:]}")

    d = fresh("not_json")
    open(run_json(d, ids[1]), "wb").write(b"\xff\xfe\x00garbage" * 100)
    r = report(d)
    check("results: a binary run.json is listed, the rest reported (exit 2)", r.returncode == 2 and ids[1] in r.stdout, r.stdout[-600:])

    # runs/<id>/timing.csv feeds only the page's per-cell timing panel: a broken one is named there
    # (file:line and column) and costs nothing else; a hostile stage name stays text.
    def timing_variant(name, mutate, pattern):
        d = fresh(name)
        for i in ids:
            f = os.path.join(d, "runs", i, "timing.csv")
            mutate(f, open(f).read().splitlines())
        r = report(d)
        html = open(os.path.join(d, "report.html"), encoding="utf-8").read()
        island = html.split('id="vobench-data">', 1)[1].split("</script>", 1)[0]
        views = json.loads(island)["views"]
        errors = [v.get("timing_error", "") for v in views]
        check(f"results: timing.csv {name}: reported (exit 0), every view says why its timing is missing",
              r.returncode == 0 and views and all(re.search(pattern, e) for e in errors) and "<" not in island,
              f"exit {r.returncode}: {errors[:2]} {r.stderr[-300:]}")

    timing_variant("binary", lambda f, l: open(f, "wb").write(b"\x00\xff" * 999), r"timing\.csv:1: not a timing\.csv header")
    def set_cell(f, l, row, column, value):  # row counts from the header (0)
        cells = l[row].split(",")
        cells[column] = value
        write(f, "\n".join(l[:row] + [",".join(cells)] + l[row + 1:]) + "\n")

    timing_variant("nan", lambda f, l: set_cell(f, l, 2, 2, "nan"),
                   r"timing\.csv:3 process_ms: 'nan' is not a finite number")
    timing_variant("extra_column", lambda f, l: write(f, "\n".join(l[:4] + [l[4] + ",7"] + l[5:]) + "\n"), r"timing\.csv:5: \d+ columns, the header has")
    timing_variant("negative", lambda f, l: set_cell(f, l, 2, 3, "-1"),
                   r"timing\.csv:3: a negative time")
    timing_variant("missing", lambda f, l: os.remove(f), r"timing\.csv: cannot read")
    timing_variant("too_large", lambda f, l: open(f, "ab").truncate(600 << 20), r"more than the \d+ a timing file may have")

    # A forged header with a hostile stage name: drawn, and the name stays a \u-escaped string.
    d = fresh("timing_hostile_stage")
    for i in ids:
        f = os.path.join(d, "runs", i, "timing.csv")
        l = open(f).read().splitlines()
        write(f, "\n".join([l[0] + ",stage_</script><script>alert(1)</script>\u2028_ms"] + [x + ",1.5" for x in l[1:]]) + "\n")
    r = report(d)
    html = open(os.path.join(d, "report.html"), encoding="utf-8").read()
    island = html.split('id="vobench-data">', 1)[1].split("</script>", 1)[0]
    stages = [s["name"] for v in json.loads(island)["views"] for s in v.get("timing", {}).get("stages", [])]
    check("results: a timing.csv stage named </script><script>… is drawn as text (exit 0, escaped in the page)",
          r.returncode == 0 and "<" not in island and any("alert(1)" in n for n in stages) and html.count("<script>") == 4,
          f"exit {r.returncode}: {stages[:3]}")


# ----- one writer per folder, listing, info, check, track ---------------------------------------------

def lock_and_cli(args, w):
    slow = config(os.path.join(w, "slow.yaml"), "slow", os.path.join(w, "slow"),
                  [{"name": "corpus", "reader": os.path.join(args.plugins, "corpus_reader_healthy.so"), "path": os.path.join(w, "empty_sequence")}],
                  [{"name": "hang", "plugin": os.path.join(args.plugins, "corpus_vo_hang_in_destroy.so")}])
    first = subprocess.Popen([args.vobench, "run", slow], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 20
    while time.time() < deadline and not cell_processes():
        time.sleep(0.05)
    second = run([args.vobench, "run", slow, "--resume"])
    third = run([args.vobench, "report", os.path.join(w, "slow")])
    check("lock: a second run on a folder in use is refused at once, naming the holder's pid",
          second.returncode != 0 and f"pid {first.pid}" in second.stderr, second.stderr[-400:])
    check("lock: so is a report on it", third.returncode != 0 and "being written by another vobench" in third.stderr, third.stderr[-400:])
    first.wait(timeout=60)
    check("lock: the first run finishes its cell (exit 0)", first.returncode == 0, first.returncode)

    env = {"VOBENCH_PLUGIN_PATH": args.plugins}
    t0 = time.time()
    r = run([args.vobench, "plugins", "list", "--json"], env=env)
    try:
        listed = json.loads(r.stdout)
    except ValueError:
        listed = None
    names = {p["name"] for p in listed} if listed else set()
    check(f"list: `plugins list --json` over crashing, hanging, noisy and non-UTF-8 plugins is valid JSON ({time.time() - t0:.1f} s)",
          r.returncode == 0 and listed is not None and {"corpus_vo", "corpus_reader"} <= names, r.stdout[:300] + r.stderr[-300:])
    check("list: the crashing and hanging entries are refused with their reason",
          "killed by signal 11" in r.stderr and "did not finish within" in r.stderr, r.stderr[-600:])
    for fault in ("ctor_stdout", "bad_utf8_strings"):
        r = run([args.vobench, "plugins", "info", os.path.join(args.plugins, f"corpus_vo_{fault}.so"), "--json"])
        try:
            json.loads(r.stdout)
            ok = r.returncode == 0
        except ValueError:
            ok = False
        check(f"info: `plugins info --json` of {fault} is valid JSON", ok, r.stdout[:300])
    r = run([args.vobench, "track", "--dataset", os.path.join(args.plugins, "corpus_reader_healthy.so"), "--path", w,
             "--algorithm", os.path.join(args.plugins, "corpus_vo_ctor_stdout.so"), "--out", os.path.join(w, "track_out"), "--json"])
    try:
        json.loads(r.stdout)
        ok = r.returncode == 0
    except ValueError:
        ok = False
    check("track: a plugin that prints to stdout leaves `track --json` valid JSON", ok, r.stdout[:300])
    # An error status that comes with a message is conformant (bad_utf8_error: its bytes are printed cleaned).
    for fault, pattern in {"exit0": r"ended \(exited with code 0\) inside a plugin call", "null_last_error": r"empty last_error",
                           "bad_utf8_error": r"(?m)^PASS ", "entry_crash": r"killed by signal 11",
                           "fork_child": r"left 1 process running after the check ended \(killed\)"}.items():
        r = run([args.vobench, "plugins", "check", "--timeout", "10", os.path.join(args.plugins, f"corpus_vo_{fault}.so")])
        last = r.stdout.strip().splitlines()[-1] if r.stdout.strip() else ""
        want_fail = fault != "bad_utf8_error"
        ok = (r.returncode == 1) == want_fail and re.search(pattern, r.stdout) and re.match(r"^(PASS|FAIL) ", last)
        check(f"check: `plugins check` on {fault} {'fails' if want_fail else 'runs'}, with a final PASS/FAIL line", bool(ok),
              f"exit {r.returncode}: {r.stdout[-500:]}")
    check("cli: no process of any cell or probe outlives it", not cell_processes(), cell_processes())


def schemas(args, w):
    """Every run.json the corpus produced, healthy and failed, and every leaderboard, against its schema."""
    try:
        import jsonschema
    except ImportError:
        print("skip  schemas: python3-jsonschema is not installed (make test installs it)")
        return
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    run_schema = load_json(os.path.join(source, "schemas", "run.schema.json"))
    board_schema = load_json(os.path.join(source, "schemas", "leaderboard.schema.json"))
    runs, boards, bad = 0, 0, []
    for sweep_out in ("vo_faults", "vo_clean", "reader_faults", "data_faults"):
        out = os.path.join(w, sweep_out)
        if not os.path.isdir(out):
            continue
        for cell in os.listdir(os.path.join(out, "runs")):
            p = os.path.join(out, "runs", cell, "run.json")
            if os.path.exists(p):
                runs += 1
                try:
                    jsonschema.validate(load_json(p), run_schema)
                except jsonschema.ValidationError as e:
                    bad.append(f"{p}: {e.message}")
        boards += 1
        try:
            jsonschema.validate(load_json(os.path.join(out, "leaderboard.json")), board_schema)
        except jsonschema.ValidationError as e:
            bad.append(f"{out}/leaderboard.json: {e.message}")
    check(f"schemas: {runs} run.json (ok and failed rows) and {boards} leaderboards validate against schemas/", runs > 50 and not bad, bad[:5])


# ----- filters (issue #20): faults in a filter, and in the timing and filters keys of a config ---------

FILTER_FAULTS = {
    "healthy": "ok",
    "wrong_size": r"filter 'corpus_filter' gave colour image is 32x48, the camera 64x48 at frame 3",
    "wrong_index": r"filter 'corpus_filter' gave frame 4 for frame 3 at frame 3",
    "crash": r"killed by signal 11 \(SIGSEGV\) at frame 3",
    "error_status": r"filter 'corpus_filter': apply failed at frame 3 \(error\): deliberately fails at frame 3",
    "nan_stamp": r"filter 'corpus_filter' gave a stamp that is not finite at frame 3",
    "drop_all": "27 dropped",  # not a failure: checked by count below
}


def filter_faults(args, w):
    p = lambda kind, f: corpus_plugin(args, kind, f)
    reader = corpus_reader(args, w)
    algos = [{"name": "constant_pose", "plugin": args.constant_pose}]
    for fault, pattern in FILTER_FAULTS.items():
        out = os.path.join(w, f"filter_{fault}")
        cfg = config(os.path.join(w, f"filter_{fault}.yaml"), f"filter {fault}", out, [reader], algos,
                     extra=f"filters:\n  - {{plugin: {json.dumps(p('filter', fault))}}}\n")
        r, _ = sweep(args, cfg, jobs=1)
        rows = runs_by_algorithm(out) if os.path.isdir(os.path.join(out, "runs")) else {}
        row = next(iter(rows.values()), None)
        if row is None:
            check(f"filters: {fault}", False, f"no row (exit {r.returncode}): {r.stderr[-600:]}")
            continue
        if pattern == "ok":
            check(f"filters: {fault} is a healthy row", row["status"] == "ok" and r.returncode == 0, row["reason"])
        elif fault == "drop_all":  # 3 frames reach the plugin, 27 are dropped: recorded as such, not as lost
            check("filters: a filter that drops frames 3-29 leaves 27 dropped frames and 3 poses",
                  row["dropped_frames"] == 27 and row["frames"] == 30, f"{row['dropped_frames']} dropped, {row['frames']} frames")
        else:
            ok = row["status"] == "failed" and re.search(pattern, row["reason"]) is not None and row["metrics"] == {}
            check(f"filters: {fault} -> failed row '{row['reason'][:100]}'", ok, f"status {row['status']}, reason {row['reason']!r}")
    check("filters: no process of any cell outlives them", not cell_processes(), f"left: {cell_processes()}")
    # The config keys: refused where they are written.
    bad = {
        "an unknown timing mode": "timing: {mode: fast}\n",
        "a speed of 0": "timing: {mode: realtime, speed: 0}\n",
        "a filter that is an odometry plugin": f"filters:\n  - {{plugin: {json.dumps(args.constant_pose)}}}\n",
        "a filter value out of range": "filters:\n  - {plugin: depth_holes, params: {fraction: [0.1, 7]}}\n",
        "a filter parameter it does not have": "filters:\n  - {plugin: depth_holes, params: {depth: 1}}\n",
    }
    for name, extra in bad.items():
        cfg = config(os.path.join(w, "filter_bad.yaml"), "bad", os.path.join(w, "filter_bad"), [reader], algos, extra=extra)
        r = run([args.vobench, "run", cfg])
        check(f"configs: {name} is refused with file:line:column", r.returncode != 0 and re.search(r"filter_bad\.yaml:\d+:\d+", r.stderr),
              r.stderr[-400:])


# ----- Python plugins and readers (issue #16): faults in user Python code ------------------------------

PY_HEAD = "import numpy as np\nimport vobench\n\n\n"
PY_FAULTS = {
    # name: (body of process(self, frame), pattern of the failed row's reason)
    "py_healthy": ("return np.eye(4), 'ok'", "ok"),
    "py_raises": ("if frame.index == 3:\n            raise ValueError('deliberate failure')\n        return np.eye(4), 'ok'",
                  r"frame 3: process\(\) raised:.*py_raises\.py\", line \d+, in process.*ValueError: deliberate failure"),
    "py_garbage": ("return 'hello'", r"frame 0: process\(\) must return \(pose, status\), it returned a str"),
    "py_wrong_shape": ("return np.eye(3), 'ok'", r"4x4 \(or 3x4\) camera-to-world matrix or \(t, q\), not an array of shape \(3, 3\)"),
    "py_not_rotation": ("m = np.eye(4)\n        m[0, 0] = 2.0\n        return m, 'ok'", r"the pose's rotation is not a rotation"),
    "py_bad_status": ("return np.eye(4), 'fine'", r"the status must be 'ok', 'lost' or 'failed', not 'fine'"),
    "py_nan_pose": ("m = np.eye(4)\n        m[0, 3] = float('nan')\n        return m, 'ok'", r"non-finite"),
    "py_keeps_view": ("self.kept = frame.rgb\n        return np.eye(4), 'ok'", r"process\(\) kept frame\.rgb after returning"),
    "py_uses_stale_frame": ("if frame.index == 0:\n            self.old = frame\n            return np.eye(4), 'ok'\n"
                            "        self.old.rgb\n        return np.eye(4), 'ok'",
                            r"frame 1: process\(\) raised:.*this frame's process\(\) call has returned"),
    "py_exits": ("import sys\n        sys.exit(3)", r"SystemExit: 3"),
    "py_hangs": ("while True:\n            pass", r"timed out after 5 s \(killed\) at frame 0"),
    "py_memory": ("self.hog = [bytearray(64 << 20) for _ in range(64)]\n        return np.eye(4), 'ok'",
                  r"exceeded the memory limit of 512 MB"),
}
PY_MODULE_FAULTS = {
    "py_missing_import": ("import numpy as np\nimport no_such_module_xyz\n",
                          r"py_missing_import\.py\", line 2.*No module named 'no_such_module_xyz'"),
    "py_syntax_error": ("import numpy as np\ndef broken(:\n", r"py_syntax_error\.py\", line 2.*SyntaxError"),
    "py_no_class": ("import numpy as np\n\n\nclass Other:\n    pass\n", r"has no class 'Odometry' \(its classes: Other\)"),
    "py_bad_params": ("class Odometry:\n    PARAMS = {'ratio': (float, 'high', 'help')}\n",
                      r"PARAMS\['ratio'\]: the default of a float must be a finite number"),
}


def python_faults(args, w):
    if not args.python:
        print("skip  python: no --python bridge given (built without pybind11?)")
        return
    seq = corpus_reader(args, w)["path"]
    mods = os.path.join(w, "py")
    for name, (body, _) in PY_FAULTS.items():
        write(os.path.join(mods, name + ".py"),
              PY_HEAD + f"class Odometry:\n    def __init__(self, camera, params, seed):\n        pass\n\n"
                        f"    def process(self, frame):\n        {body}\n")
    for name, (text, _) in PY_MODULE_FAULTS.items():
        write(os.path.join(mods, name + ".py"), text)
    reader = corpus_reader(args, w)
    algo = lambda n: {"name": n, "plugin": args.python, "params": {"module": os.path.join(mods, n + ".py")}}
    healthy = [algo("py_healthy"), {"name": "constant_pose", "plugin": args.constant_pose}]
    clean = config(os.path.join(w, "py_clean.yaml"), "py clean", os.path.join(w, "py_clean"), [reader], healthy)
    faulty = config(os.path.join(w, "py_faults.yaml"), "py faults", os.path.join(w, "py_faults"), [reader],
                    healthy + [algo(n) for n in list(PY_FAULTS)[1:] + list(PY_MODULE_FAULTS)])
    r0, _ = sweep(args, clean)
    check("python: the clean sweep succeeds", r0.returncode == 0, r0.stderr[-2000:])
    r1, seconds = sweep(args, faulty)
    check(f"python: the sweep with {len(PY_FAULTS) + len(PY_MODULE_FAULTS) - 1} Python faults finishes (exit 0, {seconds:.1f} s)",
          r1.returncode == 0 and "sweep finished" in r1.stderr, f"exit {r1.returncode}: {r1.stderr[-3000:]}")
    expected = {n: v[1] for n, v in PY_FAULTS.items()}
    expected.update({n: v[1] for n, v in PY_MODULE_FAULTS.items()})
    expect_rows("python", os.path.join(w, "py_faults"), expected)
    same_healthy("python", os.path.join(w, "py_faults"), os.path.join(w, "py_clean"))
    check("python: no process of any cell outlives it", not cell_processes(), f"left: {cell_processes()}")

    # A value the class's PARAMS does not allow is a mistake in the config, named where it was written.
    bad = config(os.path.join(w, "py_bad_value.yaml"), "py bad value", os.path.join(w, "py_bad_value"), [reader],
                 [{"name": "x", "plugin": args.python,
                   "params": {"module": os.path.join(args.examples, "template.py"), "scale": 99}}])
    r = run([args.vobench, "run", bad])
    check("python: a PARAMS value out of range is refused with file:line:column",
          r.returncode != 0 and "py_bad_value.yaml:" in r.stderr and "'scale': '99' is outside [0" in r.stderr, r.stderr[-600:])

    # Readers in Python: one healthy, one that raises at frame 5, one that returns the wrong things.
    reader_py = {
        "pyr_healthy": "",
        "pyr_raises": "        if i == 5:\n            raise KeyError('frame five is missing')\n",
        "pyr_wrong_dtype": "        if i == 2:\n            return {'rgb': np.zeros((24, 32, 3), np.float64) - 1, 'depth': 'x', 'timestamp': 0.1 * i}\n",
        "pyr_not_dict": "        if i == 1:\n            return [1, 2]\n",
    }
    for name, extra in reader_py.items():
        write(os.path.join(mods, name + ".py"), "import numpy as np\n\n\nclass Dataset:\n"
              "    def open(self, path, options):\n        self.n = 30\n\n"
              "    def describe(self):\n        gt = np.zeros((30, 8))\n        gt[:, 0] = 0.1 * np.arange(30)\n        gt[:, 7] = 1\n"
              "        return {'name': 'pyseq', 'sensor': 'synthetic', 'frame_count': 30, 'ground_truth': gt,\n"
              "                'camera': {'width': 32, 'height': 24, 'fx': 30.0, 'fy': 30.0, 'cx': 15.5, 'cy': 11.5}}\n\n"
              "    def read_frame(self, i):\n" + extra +
              "        return {'rgb': np.full((24, 32, 3), i, np.uint8), 'depth': np.ones((24, 32), np.float32), 'timestamp': 0.1 * i}\n")
    datasets = [{"name": n, "reader": args.python_dataset, "path": seq, "options": {"module": os.path.join(mods, n + ".py")}}
                for n in reader_py]
    cfg = config(os.path.join(w, "pyr.yaml"), "py readers", os.path.join(w, "pyr"), datasets,
                 [{"name": "constant_pose", "plugin": args.constant_pose}])
    r, seconds = sweep(args, cfg)
    check(f"python readers: the sweep finishes (exit 0, {seconds:.1f} s)", r.returncode == 0, r.stderr[-2000:])
    expect_rows("python readers", os.path.join(w, "pyr"), {
        "pyr_healthy": "ok",
        "pyr_raises": r"read_frame\(5\).*KeyError: 'frame five is missing'",
        "pyr_wrong_dtype": r"read_frame\(2\).*'depth' must be an H x W float \(metres\) or uint16 array",
        "pyr_not_dict": r"read_frame\(1\) must return a dict, not a list",
    }, dataset_key=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vobench", required=True)
    ap.add_argument("--plugins", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--constant-pose", required=True)
    ap.add_argument("--tum", required=True)
    ap.add_argument("--only", default="")
    ap.add_argument("--python", default="", help="the python bridge plugin (vobench_python.so)")
    ap.add_argument("--python-dataset", default="", help="the python_dataset bridge plugin")
    ap.add_argument("--examples", default="", help="plugins/odometry/python_examples")
    ap.add_argument("--open3d", default="", help="the open3d_rgbd plugin (vobench_open3d_rgbd.so)")
    args = ap.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    os.chdir(args.work)
    # A private probe cache, and short probe timeouts for the hanging entry.
    os.environ["VOBENCH_PROBE_CACHE"] = os.path.join(args.work, "probe-cache")
    os.environ["VOBENCH_PROBE_TIMEOUT"] = "3"
    t0 = time.time()
    for section in (plugin_faults, reader_faults, data_faults, config_faults, results_faults, python_faults, filter_faults, open3d_params,
                    put_vo_params, synth_inputs, plot_inputs, lock_and_cli, schemas):
        if args.only and args.only not in section.__name__:
            continue
        section(args, args.work)
    print(f"corpus: {time.time() - t0:.1f} s")
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
