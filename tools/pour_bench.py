#!/usr/bin/python3
"""The pour benchmark: the same pours in TEM, ODE and Bullet, each judged right or not.

For every scene (default scenes/bench/coins_1000.json; --with-10000 adds coins_10000.json), every
engine (tem, ode, bullet; a peer program not built is skipped with a note) and every time step
of that engine's list, one run, one process at a time. Every run is sampled every 0.01 s of
simulated time and judged by four rules:

  1. outside: no body centre outside the container box at any sample;
  2. overlap: the deepest overlap (TEM's contact detection, for every engine) stays under 1 % of
     the smallest body size at every sample;
  3. energy: the total energy (kinetic + potential) never rises from one sample to the next
     by more than --energy-tol (round-off) relative to |total| + |potential| at t = 0;
  4. at rest: every body's point speed |v| + |omega| * size is under 0.1 cm/s at every sample
     of the last 0.1 s.

A fifth figure, "creep", is printed but not judged: the largest point speed at the samples of
the last 0.5 s. Prints a markdown table, then per scene the time to a right answer of each
engine (the least wall time among its right runs) and TEM's ratio to the fastest peer.

Wall time: TEM's is `tem run`'s own (the steps and the writing of its rows every 0.01 s); a
peer's is its step loop only (TEM's measurements of its states are not timed). Peers run with
sleeping off (every body simulated to the end, as in TEM; a sleeping body's speed is zeroed,
which would pass rule 4 for free) unless --peer-sleep.

  /usr/bin/python3 tools/pour_bench.py [SCENE.json ...] [--with-10000] [--duration S]
      [--engines tem,ode,bullet] [--tem-dt LIST] [--ode-dt LIST] [--bullet-dt LIST]
      [--threads N] [--set KEY=VALUE ...] [--tem-json JSON] [--ode-args ARGS]
      [--bullet-args ARGS] [--peer-sleep] [--timeout S] [--keep DIR]

--set and --tem-json (or --tem-args) change TEM's copy of the scene only (e.g. --set
contact.substeps=4, or --tem-json '{"contact": {"max_sweeps": 40}}'); VALUE is read as JSON
when it parses, else as text. Standard library only.
"""
import argparse
import csv
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.dont_write_bytecode = True  # no __pycache__ left in tools/
import pile_check  # noqa: E402  (body sizes of a scene, as the pile judge reads them)

ENGINES = ("tem", "ode", "bullet")
DEFAULT_DTS = {"tem": "5e-4,2.5e-4,1.25e-4", "ode": "1e-4,5e-5,2e-5",
               "bullet": "1e-4,5e-5,2e-5"}
SAMPLE_EVERY = 0.01   # s of simulated time between samples
REST_SPEED = 0.1      # cm/s, rule 4
REST_WINDOW = 0.1     # s, rule 4
CREEP_WINDOW = 0.5    # s, the creep figure
OVERLAP_LIMIT = 1.0   # % of the smallest body size, rule 2


# ---------------------------------------------------------------- scene copies and overrides

def merge(base, extra):
    """`extra` merged into `base` in place, objects key by key, anything else replaced."""
    for key, value in extra.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            merge(base[key], value)
        else:
            base[key] = value
    return base


def dotted(assignment):
    """'contact.substeps=4' as {"contact": {"substeps": 4}}."""
    if "=" not in assignment:
        sys.exit("pour_bench: --set wants KEY=VALUE, got '%s'" % assignment)
    key, text = assignment.split("=", 1)
    try:
        value = json.loads(text)
    except ValueError:
        value = text
    for part in reversed(key.split(".")):
        if not part:
            sys.exit("pour_bench: --set has an empty key part in '%s'" % assignment)
        value = {part: value}
    return value


def tem_scene(scene, dt, duration, overrides, path):
    """TEM's copy: dt, duration, a row every SAMPLE_EVERY, no ParaView, no checkpoints, then the
    overrides (last, so that they can change anything)."""
    copy = json.loads(json.dumps(scene))
    copy["time_step"] = dt
    copy["duration"] = duration
    out = copy.setdefault("output", {})
    out["interval"] = SAMPLE_EVERY
    out["paraview"] = False
    out["checkpoint_interval"] = 0
    for extra in overrides:
        merge(copy, extra)
    with open(path, "w") as f:
        json.dump(copy, f, indent=1)


def smallest_size(scene):
    sizes = [pile_check.size_and_volume(shape)[0] for shape, _ in pile_check.body_template(scene)]
    sizes = [s for s in sizes if s is not None]
    return min(sizes) if sizes else None


# ---------------------------------------------------------------- the four rules

def judge(samples, moving, size, energy_tol):
    """samples: dicts with time, outside, max_depth, total, potential, max_point_speed, in time
    order. moving: bodies at or above REST_SPEED at some sample of the last REST_WINDOW."""
    end = samples[-1]["time"]
    slack = 1e-9 * max(1.0, end)
    outside = max(s["outside"] for s in samples)
    overlap = 100 * max(s["max_depth"] for s in samples) / size
    scale = abs(samples[0]["total"]) + abs(samples[0]["potential"])
    rise = max((b["total"] - a["total"] for a, b in zip(samples, samples[1:])), default=0.0)
    rise = rise / scale if scale else rise
    creep = max(s["max_point_speed"] for s in samples if s["time"] >= end - CREEP_WINDOW - slack)
    rules = {"outside": outside == 0, "overlap": overlap < OVERLAP_LIMIT,
             "energy": rise <= energy_tol, "rest": moving == 0}
    return {"outside": outside, "overlap_pct": overlap, "rise": rise, "moving": moving,
            "creep": creep, "rules": rules, "right": all(rules.values())}


def tem_samples(out_dir, box, size, end):
    """The samples of a `tem run` directory, read as a stream (10,000 bodies x 100 rows would
    not fit as dictionaries): energy.csv gives depth and energies; bodies.csv outside and
    speeds. Point speeds use the smallest body size for every body (as pile_check does)."""
    samples = []
    with open(os.path.join(out_dir, "energy.csv")) as f:
        for r in csv.DictReader(f):
            samples.append({"time": float(r["time"]), "max_depth": float(r["max_depth"]),
                            "total": float(r["total"]), "potential": float(r["potential"]),
                            "outside": 0, "max_point_speed": 0.0})
    by_time = {"%.9g" % s["time"]: s for s in samples}
    slack = 1e-9 * max(1.0, end)
    moving = set()
    with open(os.path.join(out_dir, "bodies.csv")) as f:
        rows = csv.reader(f)
        header = next(rows)
        col = {name: i for i, name in enumerate(header)}
        ix, iv, iw = col["x"], col["vx"], col["wx"]
        current_key, sample = None, None
        for r in rows:
            if r[0] != current_key:
                current_key = r[0]
                sample = by_time.get("%.9g" % float(r[0]))
                if sample is None:
                    sys.exit("pour_bench: %s/bodies.csv has time %s, energy.csv has not"
                             % (out_dir, r[0]))
                in_window = sample["time"] >= end - REST_WINDOW - slack
            p = (float(r[ix]), float(r[ix + 1]), float(r[ix + 2]))
            if box and any(not (box["min"][k] <= p[k] <= box["max"][k]) for k in range(3)):
                sample["outside"] += 1
            v = math.sqrt(sum(float(r[iv + k]) ** 2 for k in range(3)))
            w = math.sqrt(sum(float(r[iw + k]) ** 2 for k in range(3)))
            speed = v + w * size
            sample["max_point_speed"] = max(sample["max_point_speed"], speed)
            if in_window and speed >= REST_SPEED:
                moving.add(r[1])
    return samples, len(moving)


def peer_samples(path):
    with open(path) as f:
        return [{k: (int(v) if k == "outside" else float(v)) for k, v in r.items()}
                for r in csv.DictReader(f)]


# ---------------------------------------------------------------- running the engines

def find_program(name, subdir):
    candidates = [os.path.join(ROOT, "build/release/bench", subdir, name)]
    candidates += sorted(glob.glob(os.path.join(ROOT, "build/*/bench", subdir, name)))
    for c in candidates:
        if os.access(c, os.X_OK):
            return c
    return None


def last_line(text):
    """A program's last message line, fit for a markdown cell."""
    lines = text.strip().splitlines()
    return (lines[-1] if lines else "no message").replace("|", "/")


def run(cmd, timeout):
    """(returncode, stdout, stderr, seconds); returncode None when it ran past the timeout."""
    start = time.monotonic()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout or None)
        return r.returncode, r.stdout, r.stderr, time.monotonic() - start
    except subprocess.TimeoutExpired:
        return None, "", "", time.monotonic() - start


def run_tem(a, scene, dt, overrides, work, size):
    name = "tem_dt%g" % dt
    scene_file = os.path.join(work, name + ".json")
    out_dir = os.path.join(work, name)
    tem_scene(scene, dt, a.duration, overrides, scene_file)
    cmd = [a.tem, "run", scene_file, "--out", out_dir, "--threads", str(a.threads)]
    code, _, err, seconds = run(cmd, a.timeout)
    if code is None:
        return {"failed": "ran past --timeout %g s" % a.timeout}
    with open(os.path.join(work, name + ".log"), "w") as f:
        f.write(err)
    if code != 0:
        return {"failed": "tem run exit %d: %s" % (code, last_line(err))}
    # us/step times steps: the summary's seconds have three decimals only.
    m = re.search(r"tem run: (\d+) steps to t = .*\(\S+ steps/s, ([0-9.e+-]+) us/step\)", err)
    if not m:
        return {"failed": "no summary in tem's output"}
    steps = int(m.group(1))
    wall = steps * float(m.group(2)) * 1e-6
    samples, moving = tem_samples(out_dir, scene.get("container"), size, a.duration)
    if not a.keep:  # bodies.csv of 10,000 coins is about 100 MB a run
        shutil.rmtree(out_dir, ignore_errors=True)
    result = judge(samples, moving, size, a.energy_tol)
    result.update({"wall": wall, "ms_per_step": 1e3 * wall / max(steps, 1)})
    return result


def run_peer(a, engine, program, scene_path, dt, work, size):
    samples_file = os.path.join(work, "%s_dt%g.csv" % (engine, dt))
    cmd = [program, scene_path, "--dt", repr(dt), "--duration", repr(a.duration),
           "--samples", samples_file, "--sample-every", repr(SAMPLE_EVERY),
           "--rest-speed", repr(REST_SPEED), "--rest-window", repr(REST_WINDOW),
           "--creep-window", repr(CREEP_WINDOW)]
    if not a.peer_sleep:
        cmd.append("--no-sleep")
    cmd += (a.ode_args if engine == "ode" else a.bullet_args).split()
    code, out, err, _ = run(cmd, a.timeout)
    if code is None:
        return {"failed": "ran past --timeout %g s" % a.timeout}
    if code != 0:
        return {"failed": "%s exit %d: %s" % (os.path.basename(program), code, last_line(err))}
    line = [l for l in out.splitlines() if l.startswith("engine=")][-1]
    v = dict(kv.split("=", 1) for kv in line.split())
    # The peers' own size (body_size over the Model) where the scene's shapes do not give one.
    result = judge(peer_samples(samples_file), int(v["moving_last"]),
                   size or float(v["min_body_size"]), a.energy_tol)
    result.update({"wall": float(v["wall_s"]), "ms_per_step": float(v["us_per_step"]) / 1e3})
    return result


# ---------------------------------------------------------------- the report

def sig(v):
    r = float("%.3g" % v)
    return "{:,.0f}".format(r) if r >= 1000 else "%.3g" % r


def row(engine, dt, r):
    if "failed" in r:
        return "| %s | %g | - | - | - | - | - | - | - | no: %s |" % (engine, dt, r["failed"])
    broken = [k for k, ok in r["rules"].items() if not ok]
    verdict = "yes" if r["right"] else "no (" + ", ".join(broken) + ")"
    return "| %s | %g | %s | %s | %d | %s | %.1e | %d | %s | %s |" % (
        engine, dt, sig(r["wall"]), sig(r["ms_per_step"]), r["outside"], sig(r["overlap_pct"]),
        r["rise"], r["moving"], sig(r["creep"]), verdict)


def dt_list(text, flag):
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        sys.exit("pour_bench: %s wants numbers separated by commas, got '%s'" % (flag, text))
    if not values or any(not (v > 0) for v in values):
        sys.exit("pour_bench: %s wants positive time steps, got '%s'" % (flag, text))
    return values


def shown(path):
    rel = os.path.relpath(os.path.abspath(path), ROOT)
    return path if rel.startswith("..") else rel


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="*", help="default: scenes/bench/coins_1000.json")
    ap.add_argument("--with-10000", action="store_true", help="add scenes/bench/coins_10000.json")
    ap.add_argument("--duration", type=float, default=1.0, help="simulated seconds (default 1)")
    ap.add_argument("--engines", default=",".join(ENGINES))
    for e in ENGINES:
        ap.add_argument("--%s-dt" % e, default=DEFAULT_DTS[e],
                        help="time steps, comma separated (default %s)" % DEFAULT_DTS[e])
    ap.add_argument("--threads", type=int, default=1, help="tem run --threads (default 1)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a change to TEM's scene, e.g. contact.substeps=4 (repeatable)")
    ap.add_argument("--tem-json", "--tem-args", dest="tem_json", action="append", default=[],
                    metavar="JSON",
                    help="a JSON object merged into TEM's scene (repeatable)")
    ap.add_argument("--ode-args", default="", help="extra tem_ode options, e.g. '--iterations 40'")
    ap.add_argument("--bullet-args", default="", help="extra tem_bullet options")
    ap.add_argument("--peer-sleep", action="store_true", help="let ODE and Bullet put bodies "
                    "to sleep (their default; off here so every body is simulated)")
    ap.add_argument("--energy-tol", type=float, default=1e-9,
                    help="largest relative energy rise taken for round-off (default 1e-9)")
    ap.add_argument("--timeout", type=float, default=0, help="seconds per run; 0: none")
    ap.add_argument("--tem", default=os.path.join(ROOT, "build/release/tem"))
    ap.add_argument("--keep", help="keep every run's files in this directory")
    a = ap.parse_args()

    scenes = a.scenes or [os.path.join(ROOT, "scenes/bench/coins_1000.json")]
    if a.with_10000:
        scenes.append(os.path.join(ROOT, "scenes/bench/coins_10000.json"))
    overrides = []
    for text in a.tem_json:
        try:
            value = json.loads(text)
        except ValueError as e:
            sys.exit("pour_bench: --tem-json is not JSON (%s): %s" % (e, text))
        if not isinstance(value, dict):
            sys.exit("pour_bench: --tem-json wants a JSON object, got: %s" % text)
        overrides.append(value)
    overrides += [dotted(s) for s in a.set]

    engines = [e.strip() for e in a.engines.split(",") if e.strip()]
    for e in engines:
        if e not in ENGINES:
            sys.exit("pour_bench: unknown engine '%s' (tem, ode, bullet)" % e)
    programs = {}
    if "tem" in engines and not os.access(a.tem, os.X_OK):
        sys.exit("pour_bench: %s not found; build the target tem or pass --tem" % a.tem)
    for e, subdir in (("ode", "ode"), ("bullet", "bullet")):
        if e in engines:
            programs[e] = find_program("tem_" + e, subdir)
            if not programs[e]:
                print("note: tem_%s not built, %s skipped (bash scripts/install_peers.sh, re-run "
                      "cmake, build the target tem_%s)" % (e, e, e), file=sys.stderr)
                engines.remove(e)
    dts = {e: dt_list(getattr(a, "%s_dt" % e), "--%s-dt" % e) for e in ENGINES}

    print("pour benchmark: %s s simulated, samples every %g s, TEM threads %d, "
          "peers sleeping %s; load average %.2f at the start"
          % (a.duration, SAMPLE_EVERY, a.threads, "on" if a.peer_sleep else "off",
             os.getloadavg()[0]))
    if overrides:
        print("TEM scene overrides: %s" % json.dumps(overrides))
    print()
    work_root = a.keep or tempfile.mkdtemp(prefix="tem_pour_")
    for scene_path in scenes:
        with open(scene_path) as f:
            scene = json.load(f)
        size = smallest_size(scene)
        if size is None and "tem" in engines:
            sys.exit("pour_bench: %s: no prism or box body to take the size from" % scene_path)
        work = os.path.join(work_root, os.path.splitext(os.path.basename(scene_path))[0])
        os.makedirs(work, exist_ok=True)
        print("### %s\n" % shown(scene_path))
        print("| engine | dt | wall s | ms/step | outside | deepest overlap % | energy rise "
              "| moving over last 0.1 s | creep cm/s | right? |")
        print("|---|---|---|---|---|---|---|---|---|---|", flush=True)
        best = {}
        for engine in engines:
            for dt in dts[engine]:
                if engine == "tem":
                    r = run_tem(a, scene, dt, overrides, work, size)
                else:
                    r = run_peer(a, engine, programs[engine], scene_path, dt, work, size)
                print(row(engine, dt, r), flush=True)
                if r.get("right") and (engine not in best or r["wall"] < best[engine][0]):
                    best[engine] = (r["wall"], dt)
        print()
        for engine in engines:
            if engine in best:
                print("time to a right answer, %s: %s s (dt %g)"
                      % (engine, sig(best[engine][0]), best[engine][1]))
            else:
                print("time to a right answer, %s: none of its runs was right" % engine)
        peers = [best[e][0] for e in engines if e != "tem" and e in best]
        if "tem" in best and peers:
            print("TEM / fastest peer: %.3g (below 1: TEM is faster)"
                  % (best["tem"][0] / min(peers)))
        else:
            print("TEM / fastest peer: no ratio (TEM or every peer has no right run)")
        print(flush=True)
    print("load average %.2f at the end" % os.getloadavg()[0]
          + ("; files in %s" % work_root if a.keep else ""))
    if not a.keep:
        shutil.rmtree(work_root, ignore_errors=True)


if __name__ == "__main__":
    main()
