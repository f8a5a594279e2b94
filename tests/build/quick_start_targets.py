#!/usr/bin/env python3
"""The quick start builds only what runs environments (ctest quick_start_targets).

Configures the source tree as the README's first command does, in a scratch folder, and
follows what `all` depends on in the generated makefiles (CMake's Makefile2 holds one
`X/all: Y/all` rule per dependency). Fails when the default build is not Release at -O2 without link-time optimisation, when
`all` reaches a target outside ALLOWED
(a test program, the Python module, a fuzz program), and when it reaches none of the
targets the main job needs (so a change in the makefiles' shape cannot pass unseen).
    python3 tests/build/quick_start_targets.py SOURCE_DIR
"""
import re
import subprocess
import sys
import tempfile

# What the main job needs: the engine's libraries, the command and its shell files, the
# simulated board and the firmware it runs.
ALLOWED = {"hapscene_engine", "hapscene_bench", "hapscene_cli", "hapscene_serve", "hapscene",
           "hapscene_shell_files", "hapscene-board", "hapkit_firmware"}
NEEDED = {"hapscene_engine", "hapscene"}


def reached_targets(makefile2):
    """The targets `all` depends on, directly or through other targets and folders."""
    edges = {}
    for line in makefile2.splitlines():
        match = re.match(r"^(\S*all): (\S+/all)$", line)
        if match:
            edges.setdefault(match.group(1), []).append(match.group(2))
    reached, todo = set(), ["all"]
    while todo:
        for node in edges.get(todo.pop(), []):
            if node not in reached:
                reached.add(node)
                todo.append(node)
    return {m.group(1) for node in reached if (m := re.search(r"CMakeFiles/([^/]+)\.dir/all$", node))}


def main():
    source_dir = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="hapscene_quick_start.") as scratch:
        configure = subprocess.run(["cmake", "-G", "Unix Makefiles", "-S", source_dir, "-B", scratch],
                                   capture_output=True, text=True)
        if configure.returncode != 0:
            print(configure.stdout + configure.stderr)
            sys.exit("quick_start_targets: FAIL: configure")
        with open(scratch + "/CMakeFiles/Makefile2") as makefile2:
            targets = reached_targets(makefile2.read())
        with open(scratch + "/CMakeCache.txt") as cache_file:
            cache = cache_file.read()
    # The quick start's build has no debug information and no link-time optimisation.
    for setting in ("CMAKE_BUILD_TYPE:STRING=Release", "CMAKE_CXX_FLAGS_RELEASE:STRING=-O2 -DNDEBUG",
                    "HAPSCENE_LTO:BOOL=OFF"):
        if setting not in cache.splitlines():
            sys.exit(f"quick_start_targets: FAIL: the default configuration lacks {setting}")
    print("quick_start_targets: all builds", " ".join(sorted(targets)))
    extra = sorted(targets - ALLOWED)
    if extra:
        sys.exit(f"quick_start_targets: FAIL: the quick start's build compiles {', '.join(extra)}, which the "
                 "main job does not need (make it EXCLUDE_FROM_ALL and a dependency of the target tests)")
    missing = sorted(NEEDED - targets)
    if missing:
        sys.exit(f"quick_start_targets: FAIL: all does not reach {', '.join(missing)} (has the makefiles' shape changed?)")
    print("quick_start_targets: PASS")


if __name__ == "__main__":
    main()
