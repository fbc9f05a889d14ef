"""What the Python bridges do in Python: load the user's class, read its PARAMS, build the camera
object, and format a traceback. Embedded into libvobench_python_runtime.so at build time (a C++
string); the per-frame path is in C++ (python_odometry.cpp)."""
import importlib
import importlib.util
import math
import os
import sys
import traceback
import types

_loaded = 0


def load_class(module, name):
    """The class `name` of `module`: a path to a .py file (loaded under a name of its own, so two
    instances never share module state) or a dotted module name on sys.path."""
    global _loaded
    if module.endswith(".py") or os.sep in module:
        path = os.path.abspath(module)
        if not os.path.isfile(path):
            raise FileNotFoundError(f"module file '{module}' does not exist (looked at {path})")
        folder = os.path.dirname(path)
        if folder not in sys.path:
            sys.path.insert(0, folder)  # so helpers beside the module import
        _loaded += 1
        unique = f"vobench_user_{_loaded}_" + os.path.splitext(os.path.basename(path))[0].replace("-", "_")
        spec = importlib.util.spec_from_file_location(unique, path)
        if spec is None or spec.loader is None:
            raise ImportError(f"'{module}' cannot be loaded as a Python module")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[unique] = mod
        spec.loader.exec_module(mod)
    else:
        mod = importlib.import_module(module)
    if not hasattr(mod, name):
        found = sorted(k for k, v in vars(mod).items() if isinstance(v, type) and not k.startswith("_"))
        raise AttributeError(f"module '{module}' has no class '{name}' (its classes: {', '.join(found) or 'none'})")
    cls = getattr(mod, name)
    if not isinstance(cls, type):
        raise TypeError(f"'{name}' in '{module}' is a {type(cls).__name__}, not a class")
    return cls


_TYPES = {bool: "bool", int: "int", float: "double", str: "string"}


def declared_params(cls):
    """PARAMS = {"name": (type, default, "help"[, min, max])} as rows (name, type, default text, min,
    max, choices, help); type is bool, int, float, str, or a tuple of words (an enum)."""
    table = getattr(cls, "PARAMS", {}) or {}
    if not isinstance(table, dict):
        raise TypeError(f"{cls.__name__}.PARAMS must be a dict name -> (type, default, help[, min, max])")
    rows = []
    for name, spec in table.items():
        where = f"{cls.__name__}.PARAMS['{name}']"
        if not isinstance(name, str):
            raise TypeError(f"{cls.__name__}.PARAMS: the key {name!r} is not a string")
        if not isinstance(spec, (tuple, list)) or len(spec) not in (3, 5):
            raise TypeError(f"{where} must be (type, default, help) or (type, default, help, min, max)")
        kind, default, help_text = spec[0], spec[1], spec[2]
        if not isinstance(help_text, str) or not help_text.strip():
            raise TypeError(f"{where}: the third item, the help text, must be a non-empty string")
        lo, hi = (spec[3], spec[4]) if len(spec) == 5 else (None, None)
        choices = ""
        if isinstance(kind, (tuple, list)):
            if not kind or not all(isinstance(w, str) for w in kind):
                raise TypeError(f"{where}: an enum is a non-empty tuple of words")
            type_name, choices = "enum", "|".join(kind)
            text = str(default)
        elif kind in _TYPES:
            type_name = _TYPES[kind]
            if kind is bool:
                if not isinstance(default, bool):
                    raise TypeError(f"{where}: the default of a bool must be True or False")
                text = "true" if default else "false"
            elif kind is int:
                if isinstance(default, bool) or not isinstance(default, int):
                    raise TypeError(f"{where}: the default of an int must be an int")
                text = str(default)
            elif kind is float:
                if isinstance(default, bool) or not isinstance(default, (int, float)) or not math.isfinite(default):
                    raise TypeError(f"{where}: the default of a float must be a finite number")
                text = repr(float(default))
            else:
                text = str(default)
        else:
            raise TypeError(f"{where}: the type must be bool, int, float, str or a tuple of words, not {kind!r}")
        if lo is None:
            lo, hi = (-(2.0 ** 53), 2.0 ** 53) if type_name == "int" else (-math.inf, math.inf)
        rows.append((name, type_name, text, float(lo), float(hi), choices, help_text.strip()))
    return rows


def typed_values(rows, values):
    """The declared parameters' text values (validated by the host) as Python values."""
    out = {}
    for name, type_name, _default, _lo, _hi, _choices, _help in rows:
        text = values[name]
        if type_name == "bool":
            out[name] = text in ("true", "1", "on", "yes")
        elif type_name == "int":
            out[name] = int(text)
        elif type_name == "double":
            out[name] = float(text)
        else:
            out[name] = text
    return out


def camera(width, height, fx, fy, cx, cy, model, distortion):
    import numpy
    return types.SimpleNamespace(width=width, height=height, fx=fx, fy=fy, cx=cx, cy=cy,
                                 distortion_model=model, distortion=list(distortion),
                                 K=numpy.array([[fx, 0.0, cx], [0.0, fy, cy], [0.0, 0.0, 1.0]]))


def describe_error(kind, value, tb, frames=6, limit=4000):
    """The exception and the last `frames` frames of its traceback, as the failure reason."""
    lines = traceback.format_exception(kind, value, tb, limit=-frames if frames else None)
    text = "".join(lines).rstrip()
    if len(text) > limit:
        text = "…" + text[-limit:]
    return text
