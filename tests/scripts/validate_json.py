#!/usr/bin/python3
"""validate_json.py SCHEMA FILE... — validates each FILE against the JSON Schema (Debian's
python3-jsonschema); prints every violation with its path. Exit 77 (skip) when jsonschema is missing."""
import json
import sys

try:
    import jsonschema
except ImportError:
    print("python3-jsonschema is not installed (apt-get install python3-jsonschema): skipped")
    sys.exit(77)

schema = json.load(open(sys.argv[1]))
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)
bad = 0
for path in sys.argv[2:]:
    for error in validator.iter_errors(json.load(open(path))):
        bad += 1
        print(f"{path}: {'/'.join(map(str, error.absolute_path))}: {error.message}")
    print(f"{path}: {'valid' if bad == 0 else 'INVALID'}")
sys.exit(1 if bad else 0)
