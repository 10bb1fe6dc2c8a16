#!/usr/bin/env python3
"""bench/unwrap: `neuv unwrap` over every mesh in ../shared/meshes.

For each mesh and each configuration (neural fast, neural fast without the
vertex refinement, neural paper, lscm and
harmonic on the same charts: the seed is the same, so PatchNet gives the
same charts), runs the CLI with --report and tabulates, from the report: where each
chart's map came from (provenance.sources: network = MLP_f's own map,
network+refined = MLP_f's injective map then refined, lscm_after_fold = the
networks folded and LSCM flattened the chart, ...), the share of the surface
the networks mapped injectively, the networks' own qce_mean on those charts
beside LSCM's on the same charts, the final metrics and seconds per stage.
Prints a Markdown table (paste into bench/RESULTS.md) and a summary line per
configuration; --json-out keeps the rows.

usage: bench/unwrap_all.py [--neuv build/neuv] [--shared ../shared]
                           [--configs neural-fast,lscm] [--meshes spot.obj,cow.obj]
                           [--threads 2] [--timeout 900] [--json-out rows.json]
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
    ap.add_argument("--json-out", default="")
    a = ap.parse_args()
    mesh_dir = os.path.join(a.shared, "meshes")
    meshes = a.meshes.split(",") if a.meshes else sorted(
        f for f in os.listdir(mesh_dir) if f.endswith((".obj", ".off", ".ply")))
    out = tempfile.mkdtemp(prefix="neuv-bench-")
    print("| mesh | config | faces | charts | chart sources | network area | network qce | LSCM qce (same charts) | "
          "ratio | final qce_mean | flipped | overlap | packing | param s | pack s | total s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
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
            m, s, pv = r["metrics"], r["seconds"], r["provenance"]
            src = ", ".join(f"{v['charts']} {k}" for k, v in pv["sources"].items() if v["charts"] > 0)
            nq, lq = pv["network_qce_mean"], pv["lscm_qce_mean_same_charts"]
            ratio = nq / lq if nq is not None and lq else None
            f4 = lambda v: "–" if v is None else f"{v:.4f}"
            print(f"| {mesh} | {cfg} | {r['faces']} | {r['charts']} | {src} | {pv['network_area_fraction']:.3f} | "
                  f"{f4(nq)} | {f4(lq)} | {f4(ratio)} | {m['qce_mean']:.4f} | {m['flipped']} | "
                  f"{m['overlap_fraction']:.3g} | {m['packing_efficiency']:.3f} | {s['param']:.1f} | {s['pack']:.1f} | "
                  f"{s['total']:.1f} |")
            sys.stdout.flush()
            rows.append({"mesh": mesh, "config": cfg, "faces": r["faces"], "charts": r["charts"],
                         "sources": pv["sources"], "network_area": pv["network_area_fraction"],
                         "network_qce": nq, "lscm_qce": lq, "ratio": ratio, "qce_mean": m["qce_mean"],
                         "flipped": m["flipped"], "overlap": m["overlap_fraction"],
                         "packing": m["packing_efficiency"], "seconds": s})
    for cfg in a.configs.split(","):
        rs = [x for x in rows if x["config"] == cfg]
        if not rs:
            continue
        area = [x["network_area"] for x in rs]
        ratios = sorted(x["ratio"] for x in rs if x["ratio"] is not None)
        qce = sorted(x["qce_mean"] for x in rs)
        med = lambda v: (v[(len(v) - 1) // 2] + v[len(v) // 2]) / 2 if v else float("nan")
        print(f"\n{cfg}: {len(rs)} meshes; network area mean {sum(area) / len(area):.3f}, min {min(area):.3f}; "
              f"network/LSCM qce ratio median {med(ratios):.4f}; final qce_mean median {med(qce):.4f}; "
              f"flipped {sum(x['flipped'] for x in rs)}, overlapping meshes {sum(x['overlap'] > 0 for x in rs)}")
    if a.json_out:
        json.dump(rows, open(a.json_out, "w"), indent=1)


if __name__ == "__main__":
    main()
