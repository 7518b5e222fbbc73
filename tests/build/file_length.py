#!/usr/bin/python3
"""One job per file: no source file outside tests/ is longer than 600 lines.

A file that grows past it holds more than one job; split it along its seams (docs/architecture.md,
"Conventions"). Sources are the C++, Python, shell and CMake files git tracks; tests/ is exempt
(a test file follows the module it tests).

Usage: file_length.py SOURCE_DIR
"""
import os
import pathlib
import subprocess
import sys

MAX_LINES = 600
SUFFIXES = {".cpp", ".hpp", ".h", ".cc", ".py", ".sh", ".cmake"}


def is_source(relative):
    path = pathlib.PurePosixPath(relative)
    if path.parts and path.parts[0] == "tests":
        return False
    return path.suffix in SUFFIXES or path.name == "CMakeLists.txt"


def too_long(source_dir, files):
    found = []
    for relative in files:
        if not is_source(relative):
            continue
        with open(source_dir / relative, encoding="utf-8", errors="replace") as text:
            lines = sum(1 for _ in text)
        if lines > MAX_LINES:
            found.append(f"{relative}: {lines} lines (at most {MAX_LINES}: one job per file)")
    return found


def source_files(source_dir):
    """The files git tracks or would track; outside a git checkout (an unpacked release), every
    file but those of build trees (a folder holding CMakeCache.txt) and hidden folders."""
    try:
        listed = subprocess.run(["git", "-C", str(source_dir), "ls-files", "--cached", "--others",
                                 "--exclude-standard"], capture_output=True, text=True)
    except FileNotFoundError:
        listed = None
    if listed is not None and listed.returncode == 0:
        return [f for f in listed.stdout.splitlines() if (source_dir / f).is_file()]
    files = []
    for folder, subfolders, names in os.walk(source_dir):
        subfolders[:] = [d for d in subfolders if not d.startswith(".") and
                         not (pathlib.Path(folder) / d / "CMakeCache.txt").exists()]
        files += [(pathlib.Path(folder) / n).relative_to(source_dir).as_posix() for n in names]
    return files


def self_test():
    """The check fails where it must: a 601-line source outside tests/, and not a 600-line one, a
    long test file or a long data file."""
    import tempfile
    with tempfile.TemporaryDirectory() as scratch:
        root = pathlib.Path(scratch)
        files = {
            "radar/src/long.cpp": MAX_LINES + 1,
            "radar/src/fits.cpp": MAX_LINES,
            "tests/radar/test_long.cpp": 2 * MAX_LINES,
            "data/table.txt": 2 * MAX_LINES,
            "scripts/long.py": MAX_LINES + 1,
        }
        for name, count in files.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text("x\n" * count)
        found = [line.split(":")[0] for line in too_long(root, files)]
        if sorted(found) != ["radar/src/long.cpp", "scripts/long.py"]:
            print("file_length self-test: expected radar/src/long.cpp and scripts/long.py, found",
                  found)
            return False
    return True


def main():
    if not self_test():
        return 1
    source_dir = pathlib.Path(sys.argv[1])
    files = source_files(source_dir)
    sources = [f for f in files if is_source(f)]
    if len(sources) < 100:
        print(f"file_length: only {len(sources)} sources found under {source_dir}")
        return 1
    found = too_long(source_dir, files)
    for line in found:
        print(line)
    print(f"{len(sources)} sources checked, {len(found)} longer than {MAX_LINES} lines")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
