#!/usr/bin/env python3
"""The layers of the library match its folders, and no library includes a header of a library above it.

Usage: scripts/check-include-graph.py [REPO_ROOT]     (CTest: Architecture.IncludeGraph)

It reads src/CMakeLists.txt: each library's sources (dentsph_part(NAME ...) and add_library(NAME
STATIC ...)) and what each links (target_link_libraries, PUBLIC and PRIVATE alike). Then:

  1. Folders are libraries: every .cpp of a folder of src/ is built into one library (the folder's).
     A source of one folder built into another library's list is named.
  2. A header belongs to a library: a private header src/FOLDER/x.hpp to its folder's library; a
     public header include/dentsph/x.hpp to the library of the .cpp that includes it first (a .cpp's
     first include is its own header), or to none (a header of types alone, which any library may
     include).
  3. No library includes a header of a library it does not link (directly or through the libraries
     it links): each include of src/ and include/dentsph/ is checked against the link graph.
  4. The programs (apps/) include the public headers (include/dentsph/) and their own, never a
     private header of src/.

Exit status 0 when all hold; 1, listing each break as FILE: INCLUDE (why).
"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
os.chdir(ROOT)

# Libraries of one layer, which may include each other's headers and share folders: the CUDA
# backend's device code is a library of its own only because nvcc builds it, and its stage bodies
# are the step's physics kernels, shared by CPU and GPU (docs/cuda.md); its host emulation is built
# into the step, beside the device code it emulates.
PEERS = [{"dentsph_step", "dentsph_cuda"}]


def peers_of(lib):
    for group in PEERS:
        if lib in group:
            return set(group)
    return {lib}


def cmake_lists(path):
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"#[^\n]*", "", text)  # comments
    libs, links = {}, {}
    for m in re.finditer(r"(dentsph_part|add_library)\(\s*([\w:]+)([^)]*)\)", text):
        kind, name, rest = m.group(1), m.group(2), m.group(3).split()
        if kind == "add_library":
            if not rest or rest[0] not in ("STATIC", "SHARED", "OBJECT"):
                continue  # ALIAS, INTERFACE
            rest = rest[1:]
        libs[name] = [s for s in rest if s.endswith((".cpp", ".cu"))]
    for m in re.finditer(r"target_link_libraries\(\s*([\w:]+)([^)]*)\)", text):
        name = m.group(1)
        deps = [d for d in m.group(2).split() if d.startswith("dentsph_")]
        links.setdefault(name, set()).update(deps)
    return libs, links


def closure(links, name, seen=None):
    seen = set() if seen is None else seen
    for d in links.get(name, ()):
        if d not in seen:
            seen.add(d)
            closure(links, d, seen)
    return seen


INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
ANY_INCLUDE = re.compile(r'^\s*#\s*include\s+["<]([^">]+)[">]', re.M)


def includes(path):
    return INCLUDE.findall(open(path, encoding="utf-8", errors="replace").read())


def main():
    libs, links = cmake_lists("src/CMakeLists.txt")
    problems = []
    lib_of_source = {}
    folder_libs = {}
    for lib, sources in libs.items():
        for s in sources:
            if "${" in s:
                continue  # generated (the compiled-in procedure and Chart.js)
            path = os.path.normpath(os.path.join("src", s))
            lib_of_source[path] = lib
            folder = os.path.dirname(s)
            folder_libs.setdefault(folder, {}).setdefault(lib, []).append(path)
    # 1. Folders are libraries.
    lib_of_folder = {}
    for folder, by_lib in sorted(folder_libs.items()):
        owner = max(by_lib, key=lambda lib: len(by_lib[lib]))
        lib_of_folder[folder] = owner
        for lib, paths in by_lib.items():
            if lib not in peers_of(owner):
                for p in paths:
                    problems.append(f"{p}: built into {lib}, but src/{folder} is {owner}'s folder (move it, or build it "
                                    f"into {owner})")
    # 2. Public headers: the library whose .cpp includes one first.
    lib_of_public = {}
    for path, lib in lib_of_source.items():
        first = ANY_INCLUDE.findall(open(path, encoding="utf-8", errors="replace").read())[:1]
        if first and first[0].startswith("dentsph/"):
            lib_of_public.setdefault(first[0], lib)

    def lib_of_header(inc):
        if inc.startswith("dentsph/"):
            return lib_of_public.get(inc)
        return lib_of_folder.get(os.path.dirname(inc))

    # 3. Every include within src/ against the link graph.
    for dirpath, _, files in os.walk("src"):
        for f in sorted(files):
            if not f.endswith((".cpp", ".hpp", ".cu", ".cuh", ".in")):
                continue
            path = os.path.normpath(os.path.join(dirpath, f))
            lib = lib_of_source.get(path) or lib_of_folder.get(os.path.relpath(dirpath, "src"))
            if lib is None:
                continue
            allowed = set()
            for peer in peers_of(lib):
                allowed |= closure(links, peer) | {peer}
            for inc in includes(path):
                owner = lib_of_header(inc)
                if owner is not None and owner not in allowed:
                    problems.append(f"{path}: {inc} ({lib} includes a header of {owner}, which it does not link)")
    # 4. The programs use the public headers.
    for dirpath, _, files in os.walk("apps"):
        for f in sorted(files):
            if not f.endswith((".cpp", ".hpp")):
                continue
            path = os.path.join(dirpath, f)
            for inc in includes(path):
                folder = os.path.dirname(inc)
                if folder in lib_of_folder:
                    problems.append(f"{path}: {inc} (a program includes a private header of src/{folder}: make what "
                                    f"it needs public in include/dentsph/)")
    for p in problems:
        print(p)
    if problems:
        print(f"check-include-graph: {len(problems)} break(s) of the layering (rules: scripts/check-include-graph.py)")
        return 1
    print(f"check-include-graph: {len(libs)} libraries, {len(lib_of_folder)} folders of src/: the layering holds")
    return 0


if __name__ == "__main__":
    sys.exit(main())
