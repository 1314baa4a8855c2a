#!/usr/bin/env python3
"""Runs `tem mesh --json` (approximate cutting) on each closed mesh in a directory and prints a
markdown table: mesh, faces, blocks, over-coverage %, Hausdorff % of the diagonal, seconds.

Usage: tools/public_meshes.py DIR [--max-blocks N ...] [--tem PATH] [--only NAME ...]
Meshes that tem reads as open or turned are listed as skipped. The public test meshes are not
shipped with TEM (their licences vary): see docs/meshes.md for where to get them.
"""
import argparse
import json
import pathlib
import subprocess
import sys

EXTENSIONS = {".obj", ".stl", ".ply", ".off"}


def run_tem(tem, path, max_blocks):
    cmd = [tem, "mesh", str(path), "--json", "--max-blocks", str(max_blocks)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    if not lines:
        return None, done.stderr.strip().splitlines()[-1:] or [f"exit {done.returncode}"]
    return json.loads(lines[-1]), done.stderr.strip().splitlines()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", type=pathlib.Path, help="directory of mesh files")
    parser.add_argument("--max-blocks", type=int, nargs="+", default=[64],
                        help="one row per mesh and value (default 64)")
    parser.add_argument("--tem", default="build/release/tem", help="path of the tem binary")
    parser.add_argument("--only", nargs="+", help="mesh file names (without extension) to run")
    args = parser.parse_args()
    if not args.dir.is_dir():
        sys.exit(f"{args.dir}: not a directory")
    if not pathlib.Path(args.tem).exists():
        sys.exit(f"{args.tem}: no tem binary there (build it, or pass --tem)")
    files = sorted(p for p in args.dir.iterdir() if p.suffix.lower() in EXTENSIONS)
    if args.only:
        files = [p for p in files if p.stem in args.only]
    print("| mesh | faces | max blocks | blocks | over-coverage % | Hausdorff % of diagonal | seconds |")
    print("|---|---|---|---|---|---|---|")
    skipped = []
    for path in files:
        for max_blocks in args.max_blocks:
            result, messages = run_tem(args.tem, path, max_blocks)
            if result is None or not result.get("closed") or result.get("turned") or \
                    result.get("cutting") != "approximate":
                skipped.append(f"{path.name}: {messages[-1] if messages else 'not closed'}")
                break
            volume = result["volume"]
            print(f"| {path.stem} | {result['faces']} | {max_blocks} | {result['blocks']} "
                  f"| {100 * result['over_coverage'] / volume:.2f} "
                  f"| {100 * result['hausdorff'] / result['diagonal']:.2f} "
                  f"| {result['cut_seconds']:.1f} |", flush=True)
    for line in skipped:
        print(f"skipped {line}", file=sys.stderr)


if __name__ == "__main__":
    main()
