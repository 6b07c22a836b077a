#!/usr/bin/env python3
"""Writes the default suite's tests that run a Refracta executable as a list for device_check.sh.

Reads `ctest -N -V -LE long` of a build (stdin) and prints one test per line:
name<TAB>shell command (cd to its working directory, its environment, the executable under @BIN@).
Left out: render-window tests (Debian's VTK needs an X server, a lent GPU machine has none),
Python/ParaView tests (no VTK Python there), and refracta-render's bad-input cases (host-side
validation, the same on every device). refracta-render's scenes come first: later tests read
their outputs (the fixtures of the ctest suite).
"""
import re
import shlex
import sys

SKIP_NAME = re.compile(
    r"^RefractaRender\.(Bad|Surfaces\.bad|Surfaces\.too|Background\.bad|Medium\.bad|Quality\.bad|"
    r"VolumeScene|DeviceCheck|ListDevices)")
# Set per test by device_check.sh, or meaningless on the device.
DROP_ENV = ("POCL_CACHE_DIR=", "REFRACTA_KERNEL_CACHE_DIR=")


def main():
    text = sys.stdin.read()
    names = {int(n): name for n, name in re.findall(r"Test +#(\d+): (\S+)", text)}
    tests = {}
    for line in text.split("\n"):
        m = re.match(r"(\d+): Test command: (.*)", line)
        if m:
            tests[int(m.group(1))] = {"cmd": m.group(2), "env": [], "wd": "."}
            continue
        m = re.match(r"(\d+): Working Directory: (.*)", line)
        if m and int(m.group(1)) in tests:
            tests[int(m.group(1))]["wd"] = m.group(2)
            continue
        m = re.match(r"(\d+):  (\w+=.*)", line)
        if m and int(m.group(1)) in tests:
            tests[int(m.group(1))]["env"].append(m.group(2))
    bindir = sys.argv[1].rstrip("/") + "/"
    rows = []
    for number, t in sorted(tests.items()):
        name, cmd = names.get(number, ""), t["cmd"]
        if (not cmd.startswith(bindir) or "RenderingOpenGL" in cmd or
                "BenchmarkViewPass" in cmd or SKIP_NAME.match(name)):
            continue
        env = " ".join(shlex.quote(e) for e in t["env"] if not e.startswith(DROP_ENV))
        command = "mkdir -p {0} && cd {0} && env {1} {2}".format(
            shlex.quote(t["wd"]), env, cmd.replace(bindir, "@BIN@/"))
        rows.append((0 if "refracta-render" in cmd else 1, number, name, command))
    for _, _, name, command in sorted(rows):
        print(name + "\t" + command)


if __name__ == "__main__":
    main()
