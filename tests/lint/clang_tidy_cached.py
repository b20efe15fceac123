#!/usr/bin/env python3
"""clang-tidy over the project's sources, skipping those it already passed.

A source is skipped when the key of what clang-tidy would read is in the
cache file (tests/lint/clang_tidy_clean.txt): the SHA-256 of the source
preprocessed with its own compile command (every header it includes, as
included, comments kept), that command's flags, the .clang-tidy files that apply to it and
clang-tidy's version. Any change to one of them runs clang-tidy on the file
again, so the check is the same as running it on every file; only files that
passed are ever written to the cache (--update), and a cache that does not
match this machine's headers just makes every file run. Paths are
normalised (source root and build folder), so a clone elsewhere hits the
same keys.

  clang_tidy_cached.py --clang-tidy BIN -p BUILD --root SRC --files REGEX
                       [--cache FILE] [--update] [-j N]

Exit status: 0 when every file passed (or was known clean), 1 otherwise.
"""

import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys


def compile_arguments(entry):
    if "arguments" in entry:
        return list(entry["arguments"])
    return shlex.split(entry["command"])


def preprocess_command(args, source):
    """The compile command turned into `-E -P -C` to stdout: no object, no line markers, the
    comments kept (a NOLINT comment changes what clang-tidy reports)."""
    out = []
    skip = False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD") or a == source:
            continue
        out.append(a)
    return out + ["-E", "-P", "-C", source]


def normalise(text, root, build):
    return text.replace(build, "<BUILD>").replace(root, "<ROOT>")


def tidy_configs(root, source):
    """The .clang-tidy files from the source's folder up to the root (InheritParentConfig)."""
    parts = []
    folder = os.path.dirname(source)
    while True:
        path = os.path.join(folder, ".clang-tidy")
        if os.path.isfile(path):
            with open(path, "rb") as f:
                parts.append(os.path.relpath(path, root).encode() + b"\0" + f.read())
        if os.path.abspath(folder) == os.path.abspath(root) or folder == os.path.dirname(folder):
            break
        folder = os.path.dirname(folder)
    return b"\0".join(parts)


def file_key(entry, root, build, tidy_version):
    source = os.path.normpath(os.path.join(entry["directory"], entry["file"]))
    args = compile_arguments(entry)
    pre = subprocess.run(preprocess_command(args, entry["file"]), cwd=entry["directory"],
                         capture_output=True, check=False)
    if pre.returncode != 0:
        return source, None  # cannot key it: clang-tidy runs and reports
    flags = [a for a in args if a not in (entry["file"], source)]
    h = hashlib.sha256()
    h.update(tidy_version)
    h.update(normalise(" ".join(flags), root, build).encode())
    h.update(tidy_configs(root, source))
    h.update(normalise(pre.stdout.decode("utf-8", "surrogateescape"), root, build).encode(
        "utf-8", "surrogateescape"))
    return source, h.hexdigest()


def run_tidy(clang_tidy, build, source):
    r = subprocess.run([clang_tidy, "-quiet", "-p", build, source], capture_output=True, check=False)
    return r.returncode, r.stdout.decode(errors="replace") + r.stderr.decode(errors="replace")


def check(o, root, build, version, entry, key):
    """clang-tidy on one file; the key it passed with, or None (a file edited meanwhile is not cached)."""
    source = os.path.normpath(os.path.join(entry["directory"], entry["file"]))
    code, text = run_tidy(o.clang_tidy, build, source)
    if code != 0 or key is None:
        return code, text, None
    return code, text, key if file_key(entry, root, build, version)[1] == key else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clang-tidy", required=True)
    ap.add_argument("-p", dest="build", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("--files", required=True, help="regex on the absolute source path")
    ap.add_argument("--cache", default=None)
    ap.add_argument("--update", action="store_true", help="write the files that passed to the cache")
    ap.add_argument("-j", type=int, default=os.cpu_count() or 2)
    o = ap.parse_args()
    root = os.path.realpath(o.root)
    build = os.path.realpath(o.build)
    cache = o.cache or os.path.join(root, "tests", "lint", "clang_tidy_clean.txt")

    with open(os.path.join(build, "compile_commands.json")) as f:
        entries = json.load(f)
    pattern = re.compile(o.files)
    seen = set()
    selected = []
    for e in entries:
        source = os.path.normpath(os.path.join(e["directory"], e["file"]))
        if pattern.search(source) and source not in seen:
            seen.add(source)
            selected.append(e)
    # Its version, without the line naming this machine's CPU.
    version = b"\n".join(line for line in subprocess.run(
        [o.clang_tidy, "--version"], capture_output=True, check=True).stdout.splitlines()
                          if b"Host CPU" not in line)

    known = set()
    if os.path.isfile(cache):
        with open(cache) as f:
            known = {line.split()[0] for line in f if line.strip() and not line.startswith("#")}

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, o.j)) as pool:
        keys = list(pool.map(lambda e: file_key(e, root, build, version), selected))
    todo = [(e, s, k) for e, (s, k) in zip(selected, keys) if k is None or k not in known]
    print(f"clang-tidy: {len(selected)} files, {len(selected) - len(todo)} known clean, {len(todo)} to check",
          flush=True)

    failed = []
    passed = [(s, k) for s, k in keys if k is not None and k in known]
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, o.j)) as pool:
        results = pool.map(lambda t: (t[1], check(o, root, build, version, t[0], t[2])), todo)
        for source, (code, text, key) in results:
            rel = os.path.relpath(source, root)
            if code != 0:
                failed.append(rel)
                print(f"FAILED {rel}\n{text}", flush=True)
            else:
                print(f"ok {rel}", flush=True)
                if key is not None:
                    passed.append((source, key))

    if o.update:
        lines = sorted(f"{k}  {os.path.relpath(s, root)}" for s, k in passed)
        tmp = cache + ".tmp"
        with open(tmp, "w") as f:
            f.write("# clang-tidy's known-clean keys (tests/lint/clang_tidy_cached.py --update)\n")
            f.write("\n".join(lines) + "\n")
        os.replace(tmp, cache)
        print(f"cache: {len(lines)} keys written to {os.path.relpath(cache, root)}")
    if failed:
        print(f"clang-tidy failed on {len(failed)} files: {' '.join(failed)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
