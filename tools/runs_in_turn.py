#!/usr/bin/python3
"""Compares `tem` binaries on one run, taken in turn: A, B, A, B, ...

On a shared machine the time of one run says little: this project's 2-core machine at times
gives a two-thread run one core's worth (the same binary took 8.9 s or 16.4 s for the same run,
minutes apart). Taken in turn, each binary meets the same spells, and the best of several
rounds compares them; the median shows how steady the machine was. Every run's `--hash` must
agree where the binaries are meant to give the same bits (a change that only makes a step
cheaper), and the table says so.

  /usr/bin/python3 tools/runs_in_turn.py SCENE BINARY [BINARY ...] [--rounds N] [--threads T]
      [--resume-from DIR]

For two threads this is not enough: the best of a few rounds says more about the spell a run met
than about the code (a change worth 3-4 % of the forces stage came out 1.13-1.28x faster here).
Where the two versions give the same bits, put both in one binary and alternate them call by call,
timing each with a steady clock (docs/benchmarks.md, "Measuring two threads on a noisy machine").

--resume-from copies DIR (a finished `tem run`, e.g. a settled pile) before each run and resumes
it (`tem run SCENE --resume`: SCENE's duration must reach past the checkpoint). Prints, per
binary, the best and median wall seconds and the stages (ms a step) of its best run, and the
hashes. Standard library only.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

SUMMARY = re.compile(r"tem run: \d+ steps to t = \S+ s in (\S+) s")
STAGES = re.compile(r"broad phase (\S+) us, narrow phase \+ patches (\S+) us, forces (\S+) us, "
                    r"integration (\S+) us")
HASH = re.compile(r"^hash: ([0-9a-f]+)$", re.M)


def one_run(binary, scene, threads, resume_from, work):
    out = os.path.join(work, "run")
    shutil.rmtree(out, ignore_errors=True)
    command = [binary, "run", scene, "--out", out, "--threads", str(threads), "--hash"]
    if resume_from:
        shutil.copytree(resume_from, out)
        command.append("--resume")
    done = subprocess.run(command, capture_output=True, text=True)
    text = done.stdout + done.stderr
    wall, stages, digest = SUMMARY.search(text), STAGES.search(text), HASH.search(text)
    if done.returncode != 0 or not wall or not stages:
        sys.exit("runs_in_turn: %s failed (exit %d):\n%s" % (binary, done.returncode, text[-2000:]))
    return (float(wall.group(1)), [float(x) / 1000 for x in stages.groups()],
            digest.group(1) if digest else "-")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("binaries", nargs="+")
    ap.add_argument("--rounds", type=int, default=3, help="runs of each binary (default 3)")
    ap.add_argument("--threads", type=int, default=1, help="tem run --threads (default 1)")
    ap.add_argument("--resume-from", help="a finished run's directory to resume each time")
    args = ap.parse_args()
    if args.rounds < 1:
        sys.exit("runs_in_turn: --rounds must be at least 1")
    for b in args.binaries:
        if not os.access(b, os.X_OK):
            sys.exit("runs_in_turn: %s is not an executable" % b)
    runs = {b: [] for b in args.binaries}
    with tempfile.TemporaryDirectory(prefix="tem_in_turn_") as work:
        for _ in range(args.rounds):
            for b in args.binaries:
                runs[b].append(one_run(b, args.scene, args.threads, args.resume_from, work))
    print("%s, %d thread(s), %d round(s), binaries in turn" % (args.scene, args.threads,
                                                              args.rounds))
    print("| binary | best wall s | median wall s | best run's stages, ms a step "
          "(broad, narrow + patches, forces, integration) | hashes |")
    print("|---|---|---|---|---|")
    for b in args.binaries:
        best = min(runs[b], key=lambda r: r[0])
        hashes = sorted({r[2] for r in runs[b]})
        print("| %s | %.3f | %.3f | %s | %s |" % (
            b, best[0], statistics.median(r[0] for r in runs[b]),
            ", ".join("%.2f" % x for x in best[1]), " ".join(hashes)))
    all_hashes = {r[2] for rs in runs.values() for r in rs}
    print("same bits in every run: %s" % ("yes" if len(all_hashes) == 1 else "no"))


if __name__ == "__main__":
    main()
