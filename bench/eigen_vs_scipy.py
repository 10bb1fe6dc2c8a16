#!/usr/bin/python3
"""Eigenpairs (k = 64) of L phi = lambda M phi: neuv (CHOLMOD + ARPACK
shift-invert, bench_eigen) against SciPy's eigsh(L, k, M, sigma, which='LM')
on the very same matrices, side by side in one run.

usage: OPENBLAS_NUM_THREADS=1 bench/eigen_vs_scipy.py BUILD_DIR MESH... [--runs N]

bench_eigen computes the eigenpairs and writes L, M and its shift sigma to a
temporary folder; a fresh Python child then times SciPy on those files with
the same sigma and k. The two alternate for N rounds (medians are reported),
so the load of a shared machine falls on both alike. Prints seconds, the
ratio ours / SciPy, the largest relative eigenvalue difference, and peak
memory (ru_maxrss) of each side: bench_eigen's whole process (mesh, L, M,
factor, Lanczos basis), and a fresh Python child that loads L and M and runs
eigsh (its baseline after imports and loading is printed too, since the
interpreter and NumPy/SciPy alone take tens of MB)."""
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse
from scipy.sparse.linalg import eigsh


def parse_result(text):
    for line in text.splitlines():
        if line.startswith("RESULT "):
            return dict(kv.split("=", 1) for kv in line.split()[1:])
    raise RuntimeError("bench_eigen printed no RESULT line:\n" + text)


def bench_mesh(build, mesh, runs, k):
    """Alternates one neuv run and one SciPy run, `runs` rounds, so a change in
    machine load (the build machine is shared) hits both sides alike."""
    ours_s, scipy_s, ours_rss, scipy_rss, scipy_base = [], [], 0, 0, 0
    with tempfile.TemporaryDirectory(prefix="neuv-eigen-") as tmp:
        for _ in range(runs):
            proc = subprocess.run([os.path.join(build, "bench", "bench_eigen"), mesh, "--runs", "1",
                                   "--k", str(k), "--out", tmp], capture_output=True, text=True)
            if proc.returncode != 0:
                raise RuntimeError(proc.stderr)
            ours = parse_result(proc.stdout)
            ours_s.append(float(ours["median_s"]))
            ours_rss = max(ours_rss, int(ours["maxrss_kb"]))
            child = subprocess.run([sys.executable, os.path.abspath(__file__), "--scipy-child", tmp, ours["sigma"],
                                    "1", str(k)], capture_output=True, text=True)
            if child.returncode != 0:
                raise RuntimeError(child.stderr)
            theirs = parse_result(child.stdout)
            scipy_s.append(float(theirs["median_s"]))
            scipy_rss = max(scipy_rss, int(theirs["maxrss_kb"]))
            scipy_base = max(scipy_base, int(theirs["base_kb"]))
        our_evals = np.loadtxt(os.path.join(tmp, "evals.txt"))
        w = np.loadtxt(os.path.join(tmp, "scipy_evals.txt"))
    scale = max(abs(w[-1]), 1e-300)
    diff = float(np.max(np.abs(w - our_evals)) / scale)
    return {
        "mesh": os.path.basename(mesh), "vertices": int(ours["vertices"]),
        "ours_s": statistics.median(ours_s), "scipy_s": statistics.median(scipy_s),
        "ours_rss_mb": ours_rss / 1024.0, "scipy_rss_mb": scipy_rss / 1024.0,
        "scipy_base_mb": scipy_base / 1024.0, "eval_diff": diff,
    }


def scipy_child(tmp, sigma, runs, k):
    """Runs in a fresh process so ru_maxrss is SciPy's alone."""
    L = scipy.sparse.csc_matrix(scipy.io.mmread(os.path.join(tmp, "L.mtx")))
    M = scipy.sparse.csc_matrix(scipy.io.mmread(os.path.join(tmp, "M.mtx")))
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        w, _v = eigsh(L, k=k, M=M, sigma=sigma, which="LM")
        times.append(time.perf_counter() - t0)
    np.savetxt(os.path.join(tmp, "scipy_evals.txt"), np.sort(w), fmt="%.17g")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"RESULT median_s={statistics.median(times)} maxrss_kb={peak} base_kb={base}")


def main():
    args = sys.argv[1:]
    if args and args[0] == "--scipy-child":
        scipy_child(args[1], float(args[2]), int(args[3]), int(args[4]))
        return 0
    runs, k = 3, 64
    if "--runs" in args:
        i = args.index("--runs")
        runs = int(args[i + 1])
        del args[i:i + 2]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    build, meshes = args[0], args[1:]
    print(f"k = {k}, median of {runs} runs, OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}, "
          f"SciPy {scipy.__version__}")
    print(f"{'mesh':<22} {'vertices':>8} {'neuv s':>8} {'SciPy s':>8} {'ratio':>6} {'max |dλ|/λmax':>14} "
          f"{'neuv peak MB':>12} {'SciPy peak MB':>13} {'(base MB)':>9}")
    for mesh in meshes:
        r = bench_mesh(build, mesh, runs, k)
        print(f"{r['mesh']:<22} {r['vertices']:>8} {r['ours_s']:>8.3f} {r['scipy_s']:>8.3f} "
              f"{r['ours_s'] / r['scipy_s']:>6.2f} {r['eval_diff']:>14.2e} {r['ours_rss_mb']:>12.1f} "
              f"{r['scipy_rss_mb']:>13.1f} {r['scipy_base_mb']:>9.1f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
