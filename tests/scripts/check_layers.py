#!/usr/bin/env python3
"""Every #include "folder/…" in harness/src against the layer table of docs/architecture.md: a
layer uses only the layers below it. Prints each violation as file:line and exits 1 if there is any."""
import os
import re
import sys

# layer: the harness folders it may include (its own always allowed). <vobench/…> (the public
# header and SDK) is open to all; synth also uses the shared depth registration of plugins/common.
ALLOWED = {
    "util": set(),
    "metrics": {"util"},
    "abi": {"util"},
    "record": {"abi", "metrics", "util"},
    "synth": {"metrics", "util"},
    "groundtruth": {"metrics", "util"},
    "track": {"record", "abi", "metrics", "util"},
    "sweep": {"track", "record", "abi", "synth", "metrics", "util"},
    "report": {"record", "metrics", "util"},
    "cli": {"report", "sweep", "track", "record", "abi", "synth", "groundtruth", "metrics", "util"},
}

root = os.path.join(sys.argv[1], "harness", "src")
violations = []
for layer in sorted(os.listdir(root)):
    folder = os.path.join(root, layer)
    if not os.path.isdir(folder):
        continue
    if layer not in ALLOWED:
        violations.append(f"{folder}: a folder the layer table does not know (add it to docs/architecture.md and this script)")
        continue
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        for n, line in enumerate(open(path, encoding="utf-8"), 1):
            m = re.match(r'\s*#\s*include\s+"([a-z_]+)/', line)
            if m and m.group(1) != layer and m.group(1) not in ALLOWED[layer]:
                violations.append(f"{path}:{n}: {layer}/ may not include {m.group(1)}/ ({line.strip()})")
for v in violations:
    print(v)
print(f"layers: {len(violations)} violations")
sys.exit(1 if violations else 0)
