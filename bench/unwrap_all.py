#!/usr/bin/env python3
"""bench/unwrap: `neuv unwrap` over every mesh in ../shared/meshes.

For each mesh and each configuration (neural fast, neural fast without the
vertex refinement, neural paper, lscm and
harmonic on the same charts: the seed is the same, so PatchNet gives the
same charts), runs the CLI with --report and tabulates seconds per stage,
charts, qce_mean, ase_abs_mean, flipped, overlap_fraction and
packing_efficiency. Prints a Markdown table (paste into bench/RESULTS.md).

usage: bench/unwrap_all.py [--neuv build/neuv] [--shared ../shared]
                           [--configs neural-fast,lscm] [--meshes spot.obj,cow.obj]
                           [--threads 2] [--timeout 900]
"""
import argparse, json, os, subprocess, sys, tempfile, time

CONFIGS = {
    "neural-fast": ["--method", "neural", "--preset", "fast"],
    "neural-paper": ["--method", "neural", "--preset", "paper"],
    "neural-norefine": ["--method", "neural", "--preset", "fast", "--refine", "0"],
    "lscm": ["--method", "lscm"],
    "harmonic": ["--method", "harmonic"],
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--neuv", default="build/neuv")
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared"))
    ap.add_argument("--configs", default="neural-fast,lscm")
    ap.add_argument("--meshes", default="")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--timeout", type=int, default=900)
    a = ap.parse_args()
    mesh_dir = os.path.join(a.shared, "meshes")
    meshes = a.meshes.split(",") if a.meshes else sorted(
        f for f in os.listdir(mesh_dir) if f.endswith((".obj", ".off", ".ply")))
    out = tempfile.mkdtemp(prefix="neuv-bench-")
    print("| mesh | config | faces | charts | neural charts | qce_mean | ase_abs_mean | flipped | overlap | packing | "
          "operators s | patches s | param s | pack s | total s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for mesh in meshes:
        for cfg in a.configs.split(","):
            rep = os.path.join(out, f"{mesh}-{cfg}.json")
            cmd = [a.neuv, "unwrap", os.path.join(mesh_dir, mesh), "-o", os.path.join(out, f"{mesh}-{cfg}.obj"),
                   "--report", rep, "--threads", a.threads, "--quiet"] + CONFIGS[cfg]
            t = time.time()
            try:
                p = subprocess.run(cmd, capture_output=True, text=True, timeout=a.timeout)
                ok = p.returncode == 0
                err = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else f"exit {p.returncode}"
            except subprocess.TimeoutExpired:
                ok, err = False, f"timed out after {a.timeout} s"
            if not ok:
                print(f"| {mesh} | {cfg} | failed: {err} (after {time.time() - t:.0f} s) |")
                sys.stdout.flush()
                continue
            r = json.load(open(rep))
            m, s = r["metrics"], r["seconds"]
            print(f"| {mesh} | {cfg} | {r['faces']} | {r['charts']} | {r['param']['neural_charts']} | {m['qce_mean']:.4f} | {m['ase_abs_mean']:.3f} | "
                  f"{m['flipped']} | {m['overlap_fraction']:.3g} | {m['packing_efficiency']:.3f} | "
                  f"{s['operators']:.1f} | {s['patches']:.1f} | {s['param']:.1f} | {s['pack']:.1f} | {s['total']:.1f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
