"""A scenario given as a dict, written as the TOML text fogradar reads (Python's tomllib reads
TOML but does not write it)."""
import math
import numbers


def nest(mapping):
    """{"fog.lwc_g_per_m3": 0.5, "radar": {"tx_power_dbm": 10}} -> nested dicts: a dotted key
    at any level stands for its tables."""
    out = {}
    for key, value in mapping.items():
        if not isinstance(key, str) or not key:
            raise TypeError(f"scenario keys are non-empty strings, not {key!r}")
        parts = key.split(".")
        table = out
        for part in parts[:-1]:
            table = table.setdefault(part, {})
            if not isinstance(table, dict):
                raise TypeError(f"{key!r}: {part!r} is given both as a value and as a table")
        if isinstance(value, dict):
            merged = table.setdefault(parts[-1], {})
            if not isinstance(merged, dict):
                raise TypeError(f"{key!r} is given both as a value and as a table")
            for sub_key, sub_value in nest(value).items():
                merged[sub_key] = sub_value
        else:
            table[parts[-1]] = value
    return out


def _scalar(value):
    if hasattr(value, "item") and not isinstance(value, (list, tuple, dict, str)):
        value = value.item()  # a NumPy scalar
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        text = repr(value)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(value, str):
        escapes = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\t": "\\t", "\r": "\\r"}

        def escaped(c):
            if c in escapes:
                return escapes[c]
            return f"\\u{ord(c):04x}" if ord(c) < 0x20 or ord(c) == 0x7f else c

        return '"' + "".join(escaped(c) for c in value) + '"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_scalar(v) for v in value) + "]"
    raise TypeError(f"a scenario value is a number, boolean, string or list, not {value!r}")


def _inline(value):
    """A value of an array-of-tables element: a dict (a layer's `fog`) as an inline table."""
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_inline(v)}" for k, v in nest(value).items()) + " }"
    return _scalar(value)


def _is_table_array(value):
    return isinstance(value, (list, tuple)) and value and all(isinstance(v, dict) for v in value)


def dumps(mapping):
    """The TOML text of a (nested or dotted) dict, tables in the order given."""
    blocks = []

    def table(name, content):
        lines = [f"{k} = {_scalar(v)}" for k, v in content.items()
                 if not isinstance(v, dict) and not _is_table_array(v)]
        if name and (lines or not any(isinstance(v, dict) or _is_table_array(v)
                                      for v in content.values())):
            blocks.append(f"[{name}]\n" + "".join(line + "\n" for line in lines))
        elif lines:
            blocks.append("".join(line + "\n" for line in lines))
        for k, v in content.items():
            full = f"{name}.{k}" if name else k
            if isinstance(v, dict):
                table(full, v)
            elif _is_table_array(v):
                for element in v:
                    lines = [f"{ek} = {_inline(ev)}" for ek, ev in element.items()]
                    blocks.append(f"[[{full}]]\n" + "".join(line + "\n" for line in lines))

    table("", nest(mapping))
    return "\n".join(blocks)
