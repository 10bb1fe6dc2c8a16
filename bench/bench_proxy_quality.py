#!/usr/bin/env python3
"""bench/proxy quality: meshes that train on a simplified copy (issue 16).

Runs `neuv unwrap MESH` (default options: over 20k faces the networks train
on a 20k-face copy and the model is applied to the full mesh) on each mesh
given, and tabulates from the report what the issue's bar counts:

- qce_mean of the atlas, and "LSCM, same charts": the area-weighted qce_mean
  that LSCM gives on the same charts. For a network chart that is LSCM's own
  qce on it (the report's chart_list lscm_qce, computed on this mesh); for a
  chart whose map is already LSCM's or the copy's (lscm_after_fold,
  lscm_after_split, transferred) its own qce. Their ratio.
- L2 stretch, flips, overlap, packing.
- repairs on this mesh (the report's repairs with a chart id) and while
  training on the copy (chart -1, "while training on the copy"), against
  the chart count.
- the share of area the networks map injectively (network_area_fraction)
  and their own qce there (network_qce_mean, before any refinement), and
  model.heads_solved_on_mesh.
- seconds in all (the copy's training included).

usage: bench/bench_proxy_quality.py [--neuv build/neuv] [--threads 2] [--out DIR] MESH...
(for the shared meshes over 20k faces and their `neuv remesh --subdivide 1` versions).
"""
import argparse, json, os, subprocess, sys


def lscm_same_charts(r):
    num = den = 0.0
    for c in r["chart_list"]:
        q = c["lscm_qce"] if c.get("lscm_qce") is not None else c["qce"]
        if q is None:
            continue
        num += c["area"] * q
        den += c["area"]
    return num / den if den > 0 else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--neuv", default="build/neuv")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--out", default="/tmp/bench_proxy_quality")
    ap.add_argument("--extra", default="", help="more unwrap options, space-separated")
    ap.add_argument("meshes", nargs="+")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print("| mesh | faces | trained on | charts | qce_mean | LSCM, same charts | ratio | L2 stretch | flipped | overlap | "
          "packing | repairs on the mesh | repairs on the copy | network area | network qce | heads solved here | s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for mesh in a.meshes:
        name = os.path.splitext(os.path.basename(mesh))[0]
        rep = os.path.join(a.out, name + ".json")
        cmd = [a.neuv, "unwrap", mesh, "-o", os.path.join(a.out, name + ".obj"), "--report", rep,
               "--threads", a.threads, "--quiet"] + a.extra.split()
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            print(f"| {name} | failed: {p.stderr.strip()[-200:]} |")
            continue
        r = json.load(open(rep))
        m, pv, md = r["metrics"], r["provenance"], r.get("model", {})
        lq = lscm_same_charts(r)
        on_mesh = sum(1 for x in r["repairs"] if x["chart"] >= 0)
        on_copy = sum(1 for x in r["repairs"] if x["chart"] < 0 and x["what"].startswith("while training on the copy"))
        nq = pv.get("network_qce_mean")
        print(f"| {name} | {r['faces']} | {md.get('train_faces', r['faces'])} | {r['charts']} | {m['qce_mean']:.4f} | "
              f"{lq:.4f} | {m['qce_mean'] / lq:.4f} | {m['l2_stretch']:.3f} | {m['flipped']} | {m['overlap_fraction']:.2g} | "
              f"{m['packing_efficiency']:.3f} | {on_mesh} of {r['charts']} | {on_copy} | "
              f"{pv['network_area_fraction']:.3f} | {nq if nq is None else round(nq, 4)} | "
              f"{md.get('heads_solved_on_mesh', '-')} | {r['seconds']['total']:.1f} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
