#!/usr/bin/python3
"""The module order of docs/architecture.md, checked on every include of the sources:

    {cli, python} -> sweep -> experiment -> {radar, lidar, camera} -> sensor -> {propagation, stats} -> core

A module's files (its include/ and src/) may include the public headers of the modules below it
and its own; the sensors never include each other; experiment/, cli/ and python/ include no sensor
(experiment/'s registry, the one source that names them, is generated into the build tree). The
sensor kinds are the build's list (FOGRADAR_SENSOR_KINDS, the top CMakeLists.txt), so a new kind is
checked as the others are; the rules are written here, not read from the build, so that a new arrow
in CMake alone fails this check until the docs and this list agree.

Usage: module_layering.py SOURCE_DIR KIND...
"""
import pathlib
import re
import sys



def module_order(sensors):
    """Each module and the modules it may include (besides itself), transitively closed."""
    below = {
        "core": set(),
        "propagation": {"core"},
        "stats": {"core"},
        "sensor": {"propagation", "stats", "core"},
    }
    for sensor in sensors:
        below[sensor] = {"sensor"} | below["sensor"]
    below["experiment"] = {"sensor"} | below["sensor"]
    below["sweep"] = {"experiment"} | below["experiment"]
    below["cli"] = {"sweep"} | below["sweep"]
    below["python"] = {"sweep"} | below["sweep"]
    return below


INCLUDE = re.compile(r'^\s*#\s*include\s+"fogradar/([a-z_]+)/', re.MULTILINE)


def violations(source_dir, sensors):
    below = module_order(sensors)
    found = []
    for module in below:
        for path in sorted((source_dir / module).rglob("*")):
            if path.suffix not in {".cpp", ".hpp", ".h", ".cc"}:
                continue
            relative = pathlib.PurePosixPath(path.relative_to(source_dir).as_posix())
            for included in INCLUDE.findall(path.read_text(encoding="utf-8")):
                if included == module or included in below[module]:
                    continue
                found.append(f"{relative}: includes fogradar/{included}/, "
                             f"against the module order ({module} may include "
                             f"{', '.join(sorted(below[module])) or 'nothing else'})")
    return found


def self_test():
    """The check fails where it must: a lidar that includes the radar, a stats header that includes
    the sensor interface, a runner and a registry source that name a sensor, and a kind of the
    build's list (thermal) that includes another."""
    import tempfile
    with tempfile.TemporaryDirectory() as scratch:
        root = pathlib.Path(scratch)
        files = {
            "lidar/src/bad.cpp": '#include "fogradar/radar/chain.hpp"\n',
            "stats/include/fogradar/stats/bad.hpp": '#include "fogradar/sensor/sensor.hpp"\n',
            "experiment/src/runner.cpp": '#include "fogradar/camera/sensor.hpp"\n',
            "experiment/src/registry.cpp": '#include "fogradar/camera/sensor.hpp"\n',
            "thermal/src/bad.cpp": '#include "fogradar/lidar/params.hpp"\n',
            "thermal/src/ok.cpp": '#include "fogradar/sensor/sensor.hpp"\n',
            "core/src/ok.cpp": '#include "fogradar/core/units.hpp"\n',
        }
        for name, text in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        found = violations(root, ["radar", "lidar", "camera", "thermal"])
        expected = ["experiment/src/registry.cpp", "experiment/src/runner.cpp", "lidar/src/bad.cpp",
                    "stats/include/fogradar/stats/bad.hpp", "thermal/src/bad.cpp"]
        if sorted(line.split(":")[0] for line in found) != expected:
            print("module_layering self-test: expected violations in", expected, "found", found)
            return False
    return True


def main():
    if not self_test():
        return 1
    if len(sys.argv) < 3:
        print("usage: module_layering.py SOURCE_DIR KIND...")
        return 1
    source_dir = pathlib.Path(sys.argv[1])
    sensors = sys.argv[2:]
    below = module_order(sensors)
    # The check must see the tree: every module folder exists and holds sources.
    for module in below:
        if not any((source_dir / module).rglob("*.cpp")) and module != "sensor":
            print(f"module_layering: no sources under {source_dir / module}")
            return 1
    found = violations(source_dir, sensors)
    for line in found:
        print(line)
    checked = sum(1 for m in below for p in (source_dir / m).rglob("*") if p.suffix in {".cpp", ".hpp"})
    print(f"{checked} files checked, {len(found)} includes against the module order")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
