#!/usr/bin/env python3
"""Every performance target the issues set, measured in one go on this machine.

Each figure is a ratio within one run (or a time whose bound the issue fixed), so that it can be
reproduced on any machine with this one command. Each is measured REPETITIONS times, the
variants interleaved; the table shows the median and the spread (lowest to highest) of the
repetitions. Prints the table and exits with 1 when a target is missed, 2 when something could
not be measured. It is not a test: shared machines are noisy, so read the spread.

    ./scripts/build.sh all && bench/targets.py [--repetitions N] [--only GROUP,...]

Groups:
  tracer   lightcone's rays per second over raw Embree's on the same 1M-triangle grid at
           1920x1080, at rest (>= 0.70) and with the spheres at 0.9c (>= 0.60), 1 and 2 threads
  swarm    the time per camera ray among 10,000 bodies over 100 covering the same 30 % of the
           picture, unlit and lit (<= 2)
  scaling  `lightcone render scenes/street.json` at 1920x1080, the whole process on 1 thread
           over 2, at 1 and 4 samples (>= 1.8)
  setup    the whole process of a 16x16 render of 100,000 plain-colour moving spheres read from
           a scene file, less that of one sphere, per sphere (<= 10 us); the peak memory of a
           render of 100,000 spheres of distinct colours (bench_bodies.cpp) per sphere
           (<= 1.5 KB)
  png      encoding street's 1080p picture as PNG over the whole 1-thread, 1-sample process
           (<= 0.10)
  colour   the emission tables of 1,000 distinct colours (<= 50 ms) and of 1,920 bodies
           sharing one tabulated spectrum (<= 20 ms)
  stars    the whole catalogue over sky.json at 1920x1080: tracer and raster frame with stars
           over without (<= 1.10); loading the catalogue (<= 20 ms)
  raster   one raster frame over the pass-through baseline drawing its triangles: street.json
           at 640x360 and 1280x720 (<= 1.5), street-lit.json (<= 3); the 1,000-body swarm at
           1280x720 in frames per second (>= 5)
"""
import argparse
import json
import os
import platform
import random
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Unmeasured(Exception):
    pass


def log(message):
    print(message, file=sys.stderr, flush=True)


def bench_runs(build, pattern, repetitions):
    """{run name: [one JSON record per repetition, by repetition index]} from lightcone_bench."""
    command = [os.path.join(build, "lightcone_bench"), f"--benchmark_filter={pattern}",
               f"--benchmark_repetitions={repetitions}",
               "--benchmark_enable_random_interleaving=true", "--benchmark_format=json"]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          cwd=ROOT)
    if done.returncode != 0:
        raise Unmeasured(f"lightcone_bench --benchmark_filter='{pattern}' failed: "
                         f"{done.stderr.strip()[-300:]}")
    runs = {}
    for record in json.loads(done.stdout)["benchmarks"]:
        if record.get("run_type") != "iteration":
            continue
        runs.setdefault(record["run_name"], []).append(record)
    for records in runs.values():
        records.sort(key=lambda r: r.get("repetition_index", 0))
    return runs


def seconds(record):
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[record["time_unit"]]
    return record["real_time"] * scale


def series(runs, name, value):
    if name not in runs:
        raise Unmeasured(f"no benchmark {name} (is lightcone_bench current?)")
    return [value(r) for r in runs[name]]


def process(command):
    """Wall seconds and peak resident bytes of one run of a command."""
    start = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             cwd=ROOT)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    error = child.stderr.read().decode(errors="replace")
    child.stderr.close()
    if child.returncode != 0:
        raise Unmeasured(f"{' '.join(command)} failed: {error.strip()[-300:]}")
    return wall, usage.ru_maxrss * 1024


def alternate(commands, repetitions):
    """{key: [(wall, peak) per repetition]}, the commands run in a shuffled order each round."""
    out = {key: [] for key in commands}
    order = list(commands)
    for _ in range(repetitions):
        random.shuffle(order)
        for key in order:
            out[key].append(process(commands[key]))
    return out


class Table:
    def __init__(self):
        self.rows = []

    def add(self, group, name, values, bound, at_least, unit="", scale=1.0, digits=2):
        """`values`: one figure per repetition; met when the median is on the bound's side."""
        median = statistics.median(values)
        met = median >= bound if at_least else median <= bound
        self.rows.append((group, name, median * scale, min(values) * scale,
                          max(values) * scale, (">= " if at_least else "<= ") +
                          f"{bound * scale:g}{unit}", met, unit, digits))

    def print(self):
        header = ("target", "median", "spread", "bound", "met")
        lines = []
        for group, name, median, low, high, bound, met, unit, digits in self.rows:
            lines.append((f"{group}: {name}", f"{median:.{digits}f}{unit}",
                          f"{low:.{digits}f} to {high:.{digits}f}", bound,
                          "yes" if met else "NO"))
        widths = [max(len(row[i]) for row in lines + [header]) for i in range(5)]
        for row in [header] + lines:
            print("  ".join(cell.ljust(widths[i]) for i, cell in enumerate(row)).rstrip())

    def missed(self):
        return [row for row in self.rows if not row[6]]


def ratios(numerators, denominators):
    return [a / b for a, b in zip(numerators, denominators)]


def measure_tracer(table, build, repetitions, scratch):
    runs = bench_runs(build, r"Throughput_(raw_embree/single|lightcone/(static|moving))/case:0/",
                      repetitions)
    rays = lambda r: r["rays_per_s"]
    for threads in (1, 2):
        raw = series(runs, f"Throughput_raw_embree/single/case:0/threads:{threads}/real_time",
                     rays)
        for motion, bound, what in (("static", 0.70, "at rest"), ("moving", 0.60, "at 0.9c")):
            ours = series(runs, f"Throughput_lightcone/{motion}/case:0/threads:{threads}"
                          "/real_time", rays)
            table.add("tracer", f"grid {what}, {threads} thread{'s' * (threads > 1)}, "
                      f"share of raw Embree ({statistics.median(ours) / 1e6:.2f} / "
                      f"{statistics.median(raw) / 1e6:.2f} Mrays/s)",
                      ratios(ours, raw), bound, True)


def measure_swarm(table, build, repetitions, scratch):
    runs = bench_runs(build, r"DenseSwarm/bodies:(100|10000)/", repetitions)
    per_ray = lambda r: r["s_per_ray"]
    for lit in (0, 1):
        dense = series(runs, f"DenseSwarm/bodies:10000/lit:{lit}/manual_time", per_ray)
        sparse = series(runs, f"DenseSwarm/bodies:100/lit:{lit}/manual_time", per_ray)
        table.add("swarm", f"{'lit' if lit else 'unlit'} dense swarm, time per ray, 10^4 over "
                  "10^2 bodies", ratios(dense, sparse), 2.0, False)


def lightcone(build):
    return os.path.join(build, "lightcone")


def measure_scaling(table, build, repetitions, scratch):
    for samples in (1, 4):
        commands = {
            threads: [lightcone(build), "render", "scenes/street.json", "-o",
                      os.path.join(scratch, f"street-{threads}.png"), "--width", "1920",
                      "--height", "1080", "--samples", str(samples), "--threads", str(threads),
                      "--quiet"]
            for threads in (1, 2)}
        walls = alternate(commands, repetitions)
        one = [w for w, _ in walls[1]]
        two = [w for w, _ in walls[2]]
        table.add("scaling", f"street 1920x1080, {samples} sample{'s' * (samples > 1)}, whole "
                  f"process, 1 thread over 2 ({statistics.median(one):.2f} / "
                  f"{statistics.median(two):.2f} s)", ratios(one, two), 1.8, True)


def sphere_scene(path, count):
    """`count` unit spheres of 16 plain colours, each with its own velocity, seen at 16x16."""
    rng = random.Random(7)
    palette = [[round(rng.random(), 3) for _ in range(3)] for _ in range(16)]
    side = int(round(count ** (1 / 3))) + 1
    with open(path, "w") as f:
        f.write('{"camera": {"position": [0, 0, 0], "fov": 60, "width": 16, "height": 16, '
                '"samples": 1},\n "objects": [\n')
        for i in range(count):
            position = [i % side - side / 2, (i // side) % side - side / 2, -5 - i // side ** 2]
            velocity = [round(rng.uniform(-0.5, 0.5), 4), round(rng.uniform(-0.5, 0.5), 4), 0]
            f.write(('' if i == 0 else ',\n') + json.dumps(
                {"name": f"s{i}", "shape": {"sphere": {"radius": 0.3}}, "position": position,
                 "velocity": velocity, "material": {"color": palette[i % 16]}}))
        f.write('\n ],\n "sky": {"color": [0.05, 0.05, 0.1]}\n}\n')


def measure_setup(table, build, repetitions, scratch):
    count = 100_000
    many, one = os.path.join(scratch, "spheres.json"), os.path.join(scratch, "sphere.json")
    sphere_scene(many, count)
    sphere_scene(one, 1)
    commands = {n: [lightcone(build), "render", path, "-o", os.path.join(scratch, f"s{n}.png"),
                    "--quiet"] for n, path in ((count, many), (1, one))}
    runs = alternate(commands, repetitions)
    per_body = [(a - b) / (count - 1) for (a, _), (b, _) in zip(runs[count], runs[1])]
    table.add("setup", "setup per body at 10^5 bodies (whole process, less one body's)",
              per_body, 10e-6, False, " us", 1e6)
    memory = bench_runs(build, r"^BM_Bodies/bodies:100000/", repetitions)
    table.add("setup", "peak memory per body at 10^5 bodies (BM_Bodies' process peak / 10^5)",
              series(memory, "BM_Bodies/bodies:100000/iterations:1/real_time",
                     lambda r: r["peak_rss_bytes"] / r["bodies"]), 1500, False, " KB", 1e-3)


def measure_png(table, build, repetitions, scratch):
    encode = series(bench_runs(build, r"^PngEncode", repetitions), "PngEncode/real_time",
                    seconds)
    command = [lightcone(build), "render", "scenes/street.json", "-o",
               os.path.join(scratch, "street.png"), "--width", "1920", "--height", "1080",
               "--samples", "1", "--threads", "1", "--quiet"]
    walls = [w for w, _ in alternate({0: command}, repetitions)[0]]
    table.add("png", f"PNG encoding's share of street's 1-thread process "
              f"({statistics.median(encode):.3f} / {statistics.median(walls):.2f} s)",
              ratios(encode, walls), 0.10, False)


def measure_colour(table, build, repetitions, scratch):
    runs = bench_runs(build, r"^ColourTables/", repetitions)
    table.add("colour", "emission tables, 1,000 distinct colours",
              series(runs, "ColourTables/distinct_colours/real_time", seconds), 0.050, False,
              " ms", 1e3, 1)
    table.add("colour", "emission tables, one tabulated spectrum on 1,920 bodies",
              series(runs, "ColourTables/tabulated_spectrum/real_time", seconds), 0.020, False,
              " ms", 1e3, 1)


def measure_stars(table, build, repetitions, scratch):
    runs = bench_runs(build, r"^(SkyTrace|SkyRaster|StarCatalogueLoad)", repetitions)
    for kind, what in (("SkyTrace", "tracer render"), ("SkyRaster", "raster frame")):
        suffix = "/iterations:3/real_time" if kind == "SkyTrace" else "/real_time"
        with_stars = series(runs, f"{kind}/stars:1{suffix}", seconds)
        without = series(runs, f"{kind}/stars:0{suffix}", seconds)
        table.add("stars", f"sky.json 1920x1080, {what} with the catalogue over without",
                  ratios(with_stars, without), 1.10, False)
    table.add("stars", "loading the catalogue",
              series(runs, "StarCatalogueLoad", seconds), 0.020, False, " ms", 1e3, 1)


def measure_raster(table, build, repetitions, scratch):
    runs = bench_runs(build, r"^Raster(Frame|Baseline|Floor)/", repetitions)
    for scene, size, bound in (("street", "640x360", 1.5), ("street", "1280x720", 1.5),
                               ("street-lit", "640x360", 3.0)):
        frame = series(runs, f"RasterFrame/{scene}/{size}/real_time", seconds)
        baseline = series(runs, f"RasterBaseline/{scene}/{size}/real_time", seconds)
        # The floor: the same frame with its bodies shaded for nothing (RasterFloor).
        floor = series(runs, f"RasterFloor/{scene}/{size}/real_time", seconds)
        table.add("raster", f"{scene}.json {size}, frame over the pass-through baseline "
                  f"({1e3 * statistics.median(frame):.1f} / "
                  f"{1e3 * statistics.median(baseline):.1f} ms; bodies shaded for nothing: "
                  f"{statistics.median(ratios(floor, baseline)):.2f})", ratios(frame, baseline),
                  bound, False)
    frame = series(runs, "RasterFrame/swarm/1280x720/real_time", seconds)
    table.add("raster", "1,000-body swarm at 1280x720, frames per second",
              [1 / s for s in frame], 5.0, True, " fps", 1.0, 1)


# Each takes the table, the build directory, the repetitions and a scratch directory.
MEASURES = {"tracer": measure_tracer, "swarm": measure_swarm, "scaling": measure_scaling,
            "setup": measure_setup, "png": measure_png, "colour": measure_colour,
            "stars": measure_stars, "raster": measure_raster}


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repetitions", type=int, default=3, help="of each figure (3)")
    parser.add_argument("--only", default=",".join(MEASURES),
                        help="comma-separated groups (default: all)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="the build directory (build/)")
    args = parser.parse_args()
    groups = [g for g in args.only.split(",") if g]
    unknown = [g for g in groups if g not in MEASURES]
    if unknown or args.repetitions < 1:
        parser.error(f"unknown group {unknown[0]} (groups: {', '.join(MEASURES)})" if unknown
                     else "--repetitions must be at least 1")
    for tool in ("lightcone", "lightcone_bench"):
        if not os.access(os.path.join(args.build, tool), os.X_OK):
            sys.exit(f"targets.py: {os.path.join(args.build, tool)} is missing: run "
                     "./scripts/build.sh all first")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, cwd=ROOT).stdout.strip()
    print(f"lightcone {commit}{' (with uncommitted changes)' if dirty else ''}, "
          f"{time.strftime('%Y-%m-%d %H:%M %Z')}, {cpu_model()}, {os.cpu_count()} cores, "
          f"{args.repetitions} repetitions", flush=True)
    table = Table()
    failures = []
    with tempfile.TemporaryDirectory(prefix="lightcone-targets-") as scratch:
        for group in groups:
            log(f"targets.py: measuring {group}...")
            try:
                MEASURES[group](table, args.build, args.repetitions, scratch)
            except Unmeasured as e:
                failures.append(f"{group}: {e}")
    table.print()
    for failure in failures:
        print(f"not measured: {failure}")
    missed = table.missed()
    print(f"{len(table.rows) - len(missed)} of {len(table.rows)} targets met"
          + (f"; {len(failures)} group(s) not measured" if failures else ""))
    sys.exit(2 if failures else 1 if missed else 0)


if __name__ == "__main__":
    main()
