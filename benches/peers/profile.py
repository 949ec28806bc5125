#!/usr/bin/env python3
"""Where glint's time goes on a peer benchmark scene: its own code against its ray queries (Embree),
from a `perf record` of the render that speed.py times. A bench, not a test; it measures #14's
profile target (glint's own code at most the time of its ray queries).

    profile.py OUTDIR [--scene bunny-cornell] [--glint target/release/glint] [--spp 32] [--threads 1]
               [--width 320] [--height 240] [--depth 5] [--runs 1] [--top 0]

Needs `perf` (linux-perf; on virtual machines only the software event cpu-clock may work, which is the
one used) and the Python of speed.py (numpy, OpenEXR). Samples are put in four groups by where they
fall:
- queries: Embree and the TBB it links (libembree4, libtbb);
- own: the rest of glint, with libm and libc (its maths and memory calls);
- load and write: glint's functions that read the scene or write the image (tobj, the glTF, image
  and EXR readers and writers, decompression), which the render's time excludes;
- kernel: page faults and scheduling, mostly during load.
The ratio reported is own / queries; `--runs N` repeats the render and reports each run's ratio (runs
of one binary move it by about 5%). `--top N` then lists the N functions of the own group with the
most samples over all runs (inlined code counts as its caller's), each as a percentage of all samples.
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import speed  # noqa: E402  (beside this file)

# Functions of glint's binary that load the scene or write the image: not the render's time.
LOAD_WRITE = re.compile(r"tobj::|zune|png::|exr::|gltf|image::|miniz|inflate|flate2|dec2flt|from_utf8|"
                        r"crc32|toml|serde|basisu|draco|meshopt|webp")


def samples(report):
    """(group, symbol, sample count) for each line of `perf report -n --sort dso,sym` text (counts,
    not the printed percentages: those are rounded, and hundreds of rare symbols add up)."""
    for line in report.splitlines():
        m = re.match(r"\s*[0-9.]+%\s+([0-9]+)\s+(\S+)\s+\[(.)\]\s+(.*)", line)
        if not m:
            continue
        n, dso, kind, sym = int(m.group(1)), m.group(2), m.group(3), m.group(4).strip()
        if kind == "k" or dso.startswith("[kernel"):
            yield "kernel", sym, n
        elif dso.startswith(("libembree4", "libtbb")):
            yield "queries", sym, n
        elif LOAD_WRITE.search(sym):
            yield "load and write", sym, n
        else:
            yield "own", f"{sym} ({dso})" if not dso.startswith("glint") else sym, n


def groups(lines):
    """Percentages of samples per group from the lines `samples` read."""
    g = {"own": 0, "queries": 0, "load and write": 0, "kernel": 0}
    for group, _, n in lines:
        g[group] += n
    total = sum(g.values()) or 1
    return {k: 100.0 * v / total for k, v in g.items()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--scene", choices=sorted(speed.SCENES), default="bunny-cornell")
    ap.add_argument("--glint", default=str(speed.HERE.parent.parent / "target" / "release" / "glint"))
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--depth", type=int, default=5)
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--top", type=int, default=0, help="list the N own functions with the most samples")
    a = ap.parse_args()
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    parts = speed.SCENES[a.scene](out)
    if isinstance(parts, dict):
        parts["view"] = speed.gltf_view(a, parts)
    cmd, _ = speed.glint_command(a, parts, out, seed=1)
    print(f"{a.scene}, {a.width}x{a.height}, {a.spp} spp, {a.threads} thread(s), {Path(a.glint).name}")
    print("| run | own % | queries % | load and write % | kernel % | own / queries |")
    print("|---|---|---|---|---|---|")
    own, total_samples = {}, 0
    for run in range(1, a.runs + 1):
        data = out / f"glint_{run}.perf"
        r = subprocess.run(["perf", "record", "-q", "-e", "cpu-clock", "-F", "2000", "-o", str(data), "--", *cmd],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"perf record failed: {r.stderr[-500:]}")
        rep = subprocess.run(["perf", "report", "-i", str(data), "--stdio", "-n", "--no-children", "-g", "none",
                              "--sort", "dso,sym", "--percent-limit", "0"], capture_output=True, text=True)
        if rep.returncode != 0:
            sys.exit(f"perf report failed: {rep.stderr[-500:]}")
        lines = list(samples(rep.stdout))
        g = groups(lines)
        for group, sym, n in lines:
            total_samples += n
            if group == "own":
                own[sym] = own.get(sym, 0) + n
        ratio = g["own"] / g["queries"] if g["queries"] > 0 else float("inf")
        print(f"| {run} | {g['own']:.1f} | {g['queries']:.1f} | {g['load and write']:.1f} | {g['kernel']:.1f} | "
              f"{ratio:.2f} |", flush=True)
    if a.top > 0:
        print(f"\n| own function (all {a.runs} runs) | % of samples |\n|---|---|")
        for sym, n in sorted(own.items(), key=lambda kv: -kv[1])[:a.top]:
            print(f"| `{sym}` | {100.0 * n / max(total_samples, 1):.1f} |")


if __name__ == "__main__":
    main()
