#!/usr/bin/env python3
"""Compiles exactly what library.json describes, the way PlatformIO's library builder reads it:
build.srcDir, build.srcFilter (+<glob> / -<glob>, in order), build.includeDir and build.flags, for
Cortex-M4F with arm-none-eabi-gcc. Fails if the manifest names files that are missing, builds
anything outside lib/ (ports, tests, the command), or does not compile warning-free."""
import fnmatch, json, os, re, subprocess, sys, tempfile

man = json.load(open("library.json"))
b = man["build"]
src_dir, inc_dir = b["srcDir"], b["includeDir"]
flags = b.get("flags", [])
if isinstance(flags, str):
    flags = flags.split()
filters = b.get("srcFilter", ["+<*>"])
if isinstance(filters, str):
    filters = re.findall(r"[+-]<[^>]*>", filters)

files = []
for root, _, names in os.walk(src_dir):
    for n in names:
        rel = os.path.relpath(os.path.join(root, n), src_dir)
        if not rel.endswith((".c", ".cpp", ".S")):
            continue
        keep = False
        for f in filters:
            sign, pat = f[0], f[2:-1]
            if fnmatch.fnmatch(rel, pat) or fnmatch.fnmatch(rel, pat + "/*") or pat == "*":
                keep = sign == "+"
        if keep:
            files.append(os.path.join(src_dir, rel))
files.sort()
if not files:
    sys.exit("library.json selects no source files")
for f in files:
    if not f.startswith("lib/"):
        sys.exit(f"library.json builds {f}, outside the portable core")
for h in man.get("headers", []):
    if not os.path.exists(os.path.join(inc_dir, h)):
        sys.exit(f"library.json names header {h}, not found under {inc_dir}")
for ex in man.get("examples", []):
    for fn in ex["files"]:
        if not os.path.exists(os.path.join(ex["base"], fn)):
            sys.exit(f"library.json example file {ex['base']}/{fn} is missing")

cpu = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16"]
warn = ["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-Os"]
with tempfile.TemporaryDirectory() as d:
    objs = []
    for f in files:
        o = os.path.join(d, os.path.basename(f) + ".o")
        cmd = ["arm-none-eabi-gcc"] + cpu + warn + flags + ["-I" + inc_dir, "-c", f, "-o", o]
        r = subprocess.run(cmd)
        if r.returncode:
            sys.exit(f"library.json build failed: {' '.join(cmd)}")
        objs.append(o)
    # The umbrella header alone must compile in a consumer.
    c = os.path.join(d, "consumer.c")
    open(c, "w").write('#include "qorient/qorient.h"\nint qo_consumer_probe(void);\nint qo_consumer_probe(void) { return (int)QO_OK; }\n')
    r = subprocess.run(["arm-none-eabi-gcc"] + cpu + warn + flags + ["-I" + inc_dir, "-c", c, "-o", c + ".o"])
    if r.returncode:
        sys.exit("the umbrella header does not compile for Cortex-M4F")
print(f"library.json: {len(files)} core sources from {src_dir} with {inc_dir} and {flags}: build ok on Cortex-M4F")
