#!/usr/bin/env python3
"""Every performance target the issues set, measured in one go on this machine.

Each figure is a ratio within one run (or a time whose bound the issue fixed), so that it can be
reproduced on any machine with this one command. Each is measured REPETITIONS times, the
variants interleaved; the table shows the median and the spread (lowest to highest) of the
repetitions. It is not a test: shared machines are noisy, so read the spread, and the machine's
load printed around the table.

    ./scripts/build.sh all && bench/targets.py [--repetitions N] [--only GROUP,...] [--build DIR]

What is measured is what a user runs: a row that names the program (`lightcone render`,
`lightcone animate`) times its whole process on a scene at the scene's own defaults (a scene
file without a `render` section gets the automatic exposure and the filmic tone curve; the
bundled scenes fix theirs, street.json at EV -3); a row marked "in-process" calls the library
from lightcone_bench, and "at a fixed exposure (tracer only)" says that it leaves out what
the program adds (reading the scene, the exposure, the tone map, the file), to isolate the tracer.

Groups:
  tracer   in-process at a fixed exposure (tracer only): lightcone's rays per second over raw
           Embree's (rtcIntersect1 per pixel) on the same 1M-triangle grid at 1920x1080, at rest
           (>= 0.70) and with the spheres at 0.9c (>= 0.60), 1 and 2 threads
  cli      the same grid written as a scene file (bench/grid_scene.py) at its defaults:
           `lightcone render GRID -o out.png --threads 1 --quiet`, camera rays over the whole
           process's wall time, over raw Embree's rays per second on one thread measured in the
           same run, at rest (>= 0.70) and at 0.9c (>= 0.60); the grid at rest, whole process,
           automatic exposure over `--set render.exposure=0` on 1 thread and on all (<= 1.02);
           each repetition of these times the mean of three runs
  swarm    in-process at a fixed exposure (tracer only): the time per camera ray apart from the
           setup among 10,000 bodies over 100 covering the same 30 % of the picture, unlit and
           lit (<= 2)
  scaling  `lightcone render scenes/street.json` at 1920x1080 as its file says, the whole
           process on 1 thread over 2, at 1 and 4 samples (>= 1.8); each repetition of these
           times two runs of each, the runs alternated
  setup    the whole process of a 16x16 render of 100,000 plain-colour moving spheres read from
           a scene file at its defaults, less that of one sphere, per sphere (<= 10 us); the
           peak memory of an in-process render of 100,000 spheres of distinct colours at a fixed
           exposure (bench_bodies.cpp) per sphere (<= 1.5 KB)
  animate  `lightcone animate` at its defaults (the automatic exposure, metered and smoothed
           over the frames) of 24 frames at 24 fps of 20,000 moving spheres at 640x360, whole
           process, over the 24 whole `lightcone render --set camera.proper_time=i/24`
           processes of the same moments (<= 1.05)
  png      in-process PNG encoding of street's 1080p picture over the whole 1-thread, 1-sample
           `lightcone render scenes/street.json` process (<= 0.10)
  colour   in-process: the emission tables of 1,000 distinct colours (<= 50 ms) and of 1,920
           bodies sharing one tabulated spectrum (<= 20 ms); street.json at 1920x1080 as its
           file says (spectral colour) over the same with `doppler: off`, on one thread
           (bench_render.cpp's StreetDefault variants 0 and 1; <= 1.10)
  stars    in-process, sky.json as its file says at 1920x1080: tracer and raster frame with the
           whole catalogue over without (<= 1.10); loading the catalogue (<= 20 ms)
  raster   in-process: one raster frame over the pass-through baseline drawing its triangles:
           street.json at 640x360 and 1280x720 (<= 1.5), street-lit.json (<= 3); the
           1,000-body swarm at 1280x720 in frames per second (>= 5)
  hole     bodies near a black hole (issue 55), whole `lightcone render` processes on 2 threads
           of the scenes bench/hole_scenes.py writes, each over its flat twin: 25 lit balls, a
           lamp and a sun, shadows, about a hole in view, over the same without the hole
           (<= 3); scenes/infall.json and scenes/orbit.json at their own size over the same
           bodies at rest in flat space (<= 3); scenes/terrell.json with a hole of 1e-9 units
           of mass 866 units away over without (<= 1.5), and whether the two pictures are the
           same (PNG files byte for byte: 0 differing); in-process, black-hole.json's sky and
           disk at 1920x1080, 1 sample, 2 threads (BM_BlackHole, <= 0.5 s)

The default run (all groups, 3 repetitions) takes some 7 minutes on 2 cores (the hole group some
three: infall.json near the hole takes 40 s a run).

--build DIR measures any build, for instance one of an older commit:

    git worktree add /tmp/old OLD && (cd /tmp/old && ./scripts/build.sh all)
    bench/targets.py --build /tmp/old/build

It times that build's `lightcone` and `lightcone_bench`, copies taken at the start (so that a
rebuild during the run changes nothing); the scene files the program renders are this
checkout's (scenes/, and those this script writes), while lightcone_bench reads the scenes of
the source tree it was built from. A group whose benchmarks that build lacks is reported as not
measured. The first line names the commit of the build's source tree.

The machine: before the table it prints the CPU model, the cores and the load averages at the
start; after it, the load averages at the end and the cores' time that other work took during
the run. The run is called quiet only if the 1-minute load average at the start and the other
work's share during the run are both at most 0.5 per core; otherwise it prints `machine: NOT
quiet (...)` and why. (The load average at the end counts this run's own benchmarks, so the
other work is taken from the machine's busy time, /proc/stat, less this run's own CPU time.)

Exit status: 0 when every target measured is met, 1 when one is missed, 2 when something could
not be measured, whether or not the machine was quiet.
"""
import argparse
import json
import os
import platform
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from grid_scene import grid_scene, write_grid_scene
from hole_scenes import write_hole_scenes

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
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, cwd=ROOT)
    except OSError as e:  # a build relinking it, say
        raise Unmeasured(f"{command[0]} could not be run: {e.strerror}")
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
    try:
        child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                 cwd=ROOT)
    except OSError as e:  # a build relinking it, say
        raise Unmeasured(f"{command[0]} could not be run: {e.strerror}")
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    child.returncode = os.waitstatus_to_exitcode(status)
    error = child.stderr.read().decode(errors="replace")
    child.stderr.close()
    if child.returncode != 0:
        raise Unmeasured(f"{' '.join(command)} failed: {error.strip()[-300:]}")
    return wall, usage.ru_maxrss * 1024


def alternate(commands, repetitions, rounds=1):
    """{key: [(wall, peak) per repetition]}, the commands run in a shuffled order each round; a
    repetition's wall is the sum of `rounds` rounds' (so that a short process's noise averages
    out), its peak their highest."""
    out = {key: [] for key in commands}
    order = list(commands)
    for _ in range(repetitions):
        runs = {key: [] for key in commands}
        for _ in range(rounds):
            random.shuffle(order)
            for key in order:
                runs[key].append(process(commands[key]))
        for key, measured in runs.items():
            out[key].append((sum(wall for wall, _ in measured), max(peak for _, peak in measured)))
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
                      "in-process at a fixed exposure (tracer only), over raw Embree "
                      f"({statistics.median(ours) / 1e6:.2f} / "
                      f"{statistics.median(raw) / 1e6:.2f} Mrays/s)",
                      ratios(ours, raw), bound, True)


def measure_cli(table, build, repetitions, scratch):
    raw = series(bench_runs(build, r"^Throughput_raw_embree/single/case:0/threads:1/",
                            repetitions),
                 "Throughput_raw_embree/single/case:0/threads:1/real_time",
                 lambda r: r["rays_per_s"])
    camera = grid_scene()["camera"]
    rays = camera["width"] * camera["height"] * camera.get("samples", 1)
    folder = os.path.join(scratch, "grid")
    scenes = {moving: write_grid_scene(folder, moving) for moving in (False, True)}

    def render(moving, *options):
        return [lightcone(build), "render", scenes[moving], "-o",
                os.path.join(folder, "out.png"), "--quiet", *options]

    one, fixed = ("--threads", "1"), ("--set", "render.exposure=0")
    commands = {("rest", 1, "auto"): render(False, *one),
                ("moving", 1, "auto"): render(True, *one),
                ("rest", 1, "fixed"): render(False, *one, *fixed),
                ("rest", "all", "auto"): render(False),
                ("rest", "all", "fixed"): render(False, *fixed)}
    # Each a fraction of a second, against a bound of 2 %: three runs a repetition.
    rounds = 3
    walls = {key: [wall / rounds for wall, _ in runs]
             for key, runs in alternate(commands, repetitions, rounds).items()}
    for motion, bound, what in (("rest", 0.70, "at rest"), ("moving", 0.60, "at 0.9c")):
        ours = [rays / wall for wall in walls[(motion, 1, "auto")]]
        table.add("cli", f"grid {what}, 1 thread, `render` at its defaults, whole process, "
                  f"over raw Embree ({statistics.median(ours) / 1e6:.2f} / "
                  f"{statistics.median(raw) / 1e6:.2f} Mrays/s)", ratios(ours, raw), bound, True)
    for threads in (1, "all"):
        auto, exposed = walls[("rest", threads, "auto")], walls[("rest", threads, "fixed")]
        table.add("cli", f"grid at rest, {threads} thread{'s' * (threads != 1)}, whole "
                  "process, automatic exposure over render.exposure=0 "
                  f"({statistics.median(auto):.2f} / {statistics.median(exposed):.2f} s)",
                  ratios(auto, exposed), 1.02, False)


def measure_swarm(table, build, repetitions, scratch):
    runs = bench_runs(build, r"DenseSwarm/bodies:(100|10000)/", repetitions)
    per_ray = lambda r: r["s_per_ray"]
    for lit in (0, 1):
        dense = series(runs, f"DenseSwarm/bodies:10000/lit:{lit}/manual_time", per_ray)
        sparse = series(runs, f"DenseSwarm/bodies:100/lit:{lit}/manual_time", per_ray)
        table.add("swarm", f"{'lit' if lit else 'unlit'} dense swarm, in-process at a fixed "
                  "exposure (tracer only), time per ray, 10^4 over 10^2 bodies",
                  ratios(dense, sparse), 2.0, False)


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
        # A quarter to two seconds each, against a margin of a few per cent: two runs a
        # repetition.
        rounds = 2
        walls = alternate(commands, repetitions, rounds)
        one = [w / rounds for w, _ in walls[1]]
        two = [w / rounds for w, _ in walls[2]]
        table.add("scaling", f"street.json 1920x1080 as its file says, {samples} "
                  f"sample{'s' * (samples > 1)}, whole `render` process, 1 thread over 2 "
                  f"({statistics.median(one):.2f} / "
                  f"{statistics.median(two):.2f} s)", ratios(one, two), 1.8, True)


def sphere_scene(path, count, width=16, height=16):
    """`count` spheres of 16 plain colours, each with its own velocity, seen at `width` x
    `height`, without a `render` section (the program's defaults)."""
    rng = random.Random(7)
    palette = [[round(rng.random(), 3) for _ in range(3)] for _ in range(16)]
    side = int(round(count ** (1 / 3))) + 1
    with open(path, "w") as f:
        f.write('{"camera": {"position": [0, 0, 0], "fov": 60, "width": %d, "height": %d, '
                '"samples": 1},\n "objects": [\n' % (width, height))
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
    table.add("setup", "setup per body at 10^5 bodies (whole `render` process at its defaults, "
              "less one body's)", per_body, 10e-6, False, " us", 1e6)
    memory = bench_runs(build, r"^BM_Bodies/bodies:100000/", repetitions)
    table.add("setup", "peak memory per body at 10^5 bodies (in-process at a fixed exposure: "
              "BM_Bodies' process peak / 10^5)",
              series(memory, "BM_Bodies/bodies:100000/iterations:1/real_time",
                     lambda r: r["peak_rss_bytes"] / r["bodies"]), 1500, False, " KB", 1e-3)


def measure_animate(table, build, repetitions, scratch):
    count, frames, fps = 20_000, 24, 24
    scene = os.path.join(scratch, "bodies.json")
    sphere_scene(scene, count, 640, 360)
    folder = os.path.join(scratch, "frames")
    os.makedirs(folder, exist_ok=True)
    animate = [lightcone(build), "animate", scene, "--fps", str(fps), "--frames",
               f"0-{frames - 1}", "-o", os.path.join(folder, "animate-%04d.png"), "--quiet"]
    # Frame i is the picture at the camera's proper time camera.proper_time + i / fps (the
    # scene's is 0).
    renders = [[lightcone(build), "render", scene, "-o",
                os.path.join(folder, f"render-{i:04d}.png"), "--quiet", "--set",
                f"camera.proper_time={i / fps!r}"] for i in range(frames)]
    walls = {"animate": [], "renders": []}
    for _ in range(repetitions):
        for key in random.sample(sorted(walls), len(walls)):
            walls[key].append(process(animate)[0] if key == "animate" else
                              sum(process(command)[0] for command in renders))
    table.add("animate", f"`animate` at its defaults over {frames} `render` calls, {frames} "
              f"frames of {count:,} moving spheres at 640x360, whole processes "
              f"({statistics.median(walls['animate']):.2f} / "
              f"{statistics.median(walls['renders']):.2f} s)",
              ratios(walls["animate"], walls["renders"]), 1.05, False)


def measure_png(table, build, repetitions, scratch):
    encode = series(bench_runs(build, r"^PngEncode", repetitions), "PngEncode/real_time",
                    seconds)
    command = [lightcone(build), "render", "scenes/street.json", "-o",
               os.path.join(scratch, "street.png"), "--width", "1920", "--height", "1080",
               "--samples", "1", "--threads", "1", "--quiet"]
    walls = [w for w, _ in alternate({0: command}, repetitions)[0]]
    table.add("png", f"PNG encoding (in-process) over street's whole 1-thread `render` process "
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
    street = bench_runs(build, r"^BM_StreetDefault/variant:[01]/", repetitions)
    spectral, off = (series(street, f"BM_StreetDefault/variant:{v}/iterations:3/real_time",
                            seconds) for v in (0, 1))
    table.add("colour", f"street.json 1920x1080 as its file says, spectral colour over "
              f"doppler: off, in-process, 1 thread ({statistics.median(spectral):.2f} / "
              f"{statistics.median(off):.2f} s)", ratios(spectral, off), 1.10, False)


def measure_stars(table, build, repetitions, scratch):
    runs = bench_runs(build, r"^(SkyTrace|SkyRaster|StarCatalogueLoad)", repetitions)
    for kind, what in (("SkyTrace", "tracer render"), ("SkyRaster", "raster frame")):
        suffix = "/iterations:3/real_time" if kind == "SkyTrace" else "/real_time"
        with_stars = series(runs, f"{kind}/stars:1{suffix}", seconds)
        without = series(runs, f"{kind}/stars:0{suffix}", seconds)
        table.add("stars", f"sky.json 1920x1080, in-process {what} with the catalogue over "
                  "without",
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
        table.add("raster", f"{scene}.json {size}, in-process frame over the pass-through "
                  "baseline "
                  f"({1e3 * statistics.median(frame):.1f} / "
                  f"{1e3 * statistics.median(baseline):.1f} ms; bodies shaded for nothing: "
                  f"{statistics.median(ratios(floor, baseline)):.2f})", ratios(frame, baseline),
                  bound, False)
    frame = series(runs, "RasterFrame/swarm/1280x720/real_time", seconds)
    table.add("raster", "1,000-body swarm at 1280x720, frames per second",
              [1 / s for s in frame], 5.0, True, " fps", 1.0, 1)


def measure_hole(table, build, repetitions, scratch):
    folder = os.path.join(scratch, "hole")
    paths = write_hole_scenes(folder)
    scenes = {"lit-hole": paths["lit-balls-hole.json"], "lit-flat": paths["lit-balls-flat.json"],
              "infall": "scenes/infall.json", "infall-flat": paths["infall-flat.json"],
              "orbit": "scenes/orbit.json", "orbit-flat": paths["orbit-flat.json"],
              "terrell-hole": paths["terrell-hole.json"], "terrell": "scenes/terrell.json"}
    output = {key: os.path.join(folder, f"{key}.png") for key in scenes}
    commands = {key: [lightcone(build), "render", scene, "-o", output[key], "--threads", "2",
                      "--quiet"] for key, scene in scenes.items()}
    walls = {key: [wall for wall, _ in runs]
             for key, runs in alternate(commands, repetitions).items()}
    for key, flat, bound, what in (
            ("lit-hole", "lit-flat", 3.0, "25 lit balls, a lamp and a sun, shadows, a hole in "
             "view (640x360, 1 sample)"),
            ("infall", "infall-flat", 3.0, "scenes/infall.json (960x540, 4 samples)"),
            ("orbit", "orbit-flat", 3.0, "scenes/orbit.json (960x540, 4 samples, lit)"),
            ("terrell-hole", "terrell", 1.5, "scenes/terrell.json with a negligible hole "
             "(1e-9 M, 866 units away)")):
        table.add("hole", f"{what}, whole `render` process, 2 threads, over the same without "
                  f"the hole ({statistics.median(walls[key]):.2f} / "
                  f"{statistics.median(walls[flat]):.2f} s)", ratios(walls[key], walls[flat]),
                  bound, False)
    with open(output["terrell-hole"], "rb") as a, open(output["terrell"], "rb") as b:
        same = a.read() == b.read()
    table.add("hole", "scenes/terrell.json with the negligible hole: PNG files that differ from "
              "the picture without it", [0 if same else 1], 0, False, digits=0)
    table.add("hole", "black-hole.json sky and disk 1920x1080, 1 sample, 2 threads, in-process "
              "(BM_BlackHole)",
              series(bench_runs(build, r"^BM_BlackHole/", repetitions),
                     "BM_BlackHole/iterations:5/real_time", seconds), 0.5, False, " s", 1.0)


# Each takes the table, the build directory, the repetitions and a scratch directory.
MEASURES = {"tracer": measure_tracer, "cli": measure_cli, "swarm": measure_swarm,
            "scaling": measure_scaling, "setup": measure_setup, "animate": measure_animate,
            "png": measure_png, "colour": measure_colour, "stars": measure_stars,
            "raster": measure_raster, "hole": measure_hole}


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


PROGRAMS = ("lightcone", "lightcone_bench")


def snapshot(build, scratch):
    """A copy of the build's programs in `scratch`, with its data/ (the star catalogue, which
    the programs look for beside themselves) linked beside them: the whole run times one build,
    even while build/ is being rebuilt. Returns the copy's folder."""
    copy = os.path.join(scratch, "build")
    os.makedirs(copy)
    for program in PROGRAMS:
        shutil.copy2(os.path.join(build, program), copy)
    os.symlink(os.path.join(build, "data"), os.path.join(copy, "data"))
    return copy


def source_tree(build):
    """The source tree a build was configured from (its CMakeCache.txt), else this checkout."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return ROOT


def busy_seconds():
    """The CPU seconds all the machine's cores have spent busy since boot (/proc/stat: user,
    nice, system, irq, softirq and steal), or None where that cannot be read."""
    try:
        with open("/proc/stat") as f:
            fields = f.readline().split()
    except OSError:
        return None
    if not fields or fields[0] != "cpu" or len(fields) < 9:
        return None
    user, nice, system, _, _, irq, softirq, steal = (int(v) for v in fields[1:9])
    return (user + nice + system + irq + softirq + steal) / os.sysconf("SC_CLK_TCK")


def own_seconds():
    """The CPU seconds this script and the children it has waited for have spent."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def loads(load):
    return " ".join(f"{v:.2f}" for v in load)


class Machine:
    """The load before and after a run: quiet only if the 1-minute load average at the start
    and the other work during the run are both at most 0.5 per core."""

    QUIET_LOAD_PER_CORE = 0.5

    def __init__(self):
        self.cores = os.cpu_count() or 1
        self.start_load = os.getloadavg()
        self.start_busy, self.start_own = busy_seconds(), own_seconds()
        self.start_wall = time.perf_counter()

    def start_line(self):
        return (f"machine: {cpu_model()}, {self.cores} cores; load average "
                f"{loads(self.start_load)} (1, 5, 15 minutes) at the start")

    def end_lines(self):
        """The end's load, the other work's share of the cores during the run, and whether the
        run was quiet."""
        end_load, end_busy = os.getloadavg(), busy_seconds()
        wall = time.perf_counter() - self.start_wall
        limit = self.QUIET_LOAD_PER_CORE * self.cores
        lines = [f"machine: load average {loads(end_load)} at the end (this run's own work "
                 "included)"]
        noisy = []
        if self.start_load[0] > limit:
            noisy.append(f"load {self.start_load[0]:.2f} on {self.cores} cores at the start")
        if end_busy is None or self.start_busy is None:
            lines.append("machine: the other work during the run is unknown (no /proc/stat)")
            noisy.append("the other work during the run is unknown")
        else:
            others = max(0.0, end_busy - self.start_busy - (own_seconds() - self.start_own))
            share = others / wall
            lines.append(f"machine: other work took {share:.2f} of the {self.cores} cores during "
                         f"the run ({others:.0f} CPU s in {wall:.0f} s)")
            if share > limit:
                noisy.append(f"other work took {share:.2f} of {self.cores} cores during the run")
        lines.append(f"machine: NOT quiet ({'; '.join(noisy)})" if noisy else "machine: quiet")
        return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repetitions", type=int, default=3, help="of each figure (3)")
    parser.add_argument("--only", default=",".join(MEASURES),
                        help="comma-separated groups (default: all)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"),
                        help="the build directory whose lightcone and lightcone_bench are timed "
                        "(build/)")
    args = parser.parse_args()
    groups = [g for g in args.only.split(",") if g]
    unknown = [g for g in groups if g not in MEASURES]
    if unknown or args.repetitions < 1:
        parser.error(f"unknown group {unknown[0]} (groups: {', '.join(MEASURES)})" if unknown
                     else "--repetitions must be at least 1")
    build = os.path.abspath(args.build)
    for tool in PROGRAMS:
        if not os.access(os.path.join(build, tool), os.X_OK):
            sys.exit(f"targets.py: {os.path.join(build, tool)} is missing: run "
                     "./scripts/build.sh all first")
    machine = Machine()
    source = source_tree(build)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=source).stdout.strip() or "unknown commit"
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, cwd=source).stdout.strip()
    print(f"lightcone {commit}{' (with uncommitted changes)' if dirty else ''}, build {build}, "
          f"{time.strftime('%Y-%m-%d %H:%M %Z')}, {args.repetitions} repetitions", flush=True)
    print(machine.start_line(), flush=True)
    table = Table()
    failures = []
    with tempfile.TemporaryDirectory(prefix="lightcone-targets-") as scratch:
        programs = snapshot(build, scratch)
        for group in groups:
            log(f"targets.py: measuring {group}...")
            try:
                MEASURES[group](table, programs, args.repetitions, scratch)
            except Unmeasured as e:
                failures.append(f"{group}: {e}")
    table.print()
    for line in machine.end_lines():
        print(line)
    for failure in failures:
        print(f"not measured: {failure}")
    missed = table.missed()
    print(f"{len(table.rows) - len(missed)} of {len(table.rows)} targets met"
          + (f"; {len(failures)} group(s) not measured" if failures else ""))
    sys.exit(2 if failures else 1 if missed else 0)


if __name__ == "__main__":
    main()
