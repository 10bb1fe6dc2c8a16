#!/usr/bin/env python3
"""A saved model applied to independent remeshes of its source surface.

For each mesh: `neuv unwrap --save-model --refine 0` on the shared file (the
source atlas; --refine 0 as when the figures in bench/RESULTS.md were
measured, when --save-model still turned the refinement off), then `neuv remesh --faces` at 0.5x, 2x and 4x its face count (an
isotropic remesher: no vertex or edge shared with the source except by
chance) and the same remeshes with `--jitter` (vertices moved within the
surface, flat edges flipped). On each target:
  model      `neuv unwrap --model`: the model's charts and map
  lscm       `neuv unwrap --model --lscm-baseline`: the same charts flattened
             by LSCM on the target and placed onto the model's map by a
             similarity (what a classic tool could do with the charts)
and `neuv compare SOURCE TARGET` for UV distance (in the matched chart, and
at the nearest point whatever its chart), chart agreement (plain closest
point; "agree_f" with each face located on the source faces facing its
way), flips, overlap.
Beside them: two independent unwraps of the source (seeds 1 and 2), what a
user gets without a model.

Apply time: the median of --runs wall-clock runs of `neuv unwrap --model` on
each target (the process, loading included), and in the same run the median
for --lscm-baseline as the reference.

Usage: bench/bench_transfer_remesh.py BUILD_DIR [--out DIR] [--meshes spot,cow,...]
       [--threads T] [--runs N]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

SHARED = os.environ.get("NEUV_SHARED", os.path.join(os.path.dirname(__file__), "..", "..", "shared"))
SCALES = [0.5, 2, 4]


def run(cmd):
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr.strip()))
    return p.stdout, dt


def mesh_path(name):
    for ext in (".obj", ".off", ".ply"):
        p = os.path.join(SHARED, "meshes", name + ext)
        if os.path.exists(p):
            return p
    sys.exit("no mesh named %s in %s/meshes" % (name, SHARED))


def compare(neuv, a, b):
    out, _ = run([neuv, "compare", a, b, "--json"])
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--out", default="/tmp/bench_transfer_remesh")
    ap.add_argument("--meshes", default="spot,cow,fertility,homer,teapot")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    neuv = os.path.join(args.build, "neuv")
    os.makedirs(args.out, exist_ok=True)
    th = ["--threads", str(args.threads), "--quiet"]
    head = "%-10s %-8s %6s %-6s %9s %9s %9s %7s %7s %6s %5s %8s %5s %7s %7s %7s" % (
        "mesh", "target", "faces", "map", "uv_mean", "uv_p95", "nearest", "agree", "agree_f", "past", "flips", "overlap",
        "moved", "net", "qce", "apply_s")
    print(head)
    rows = []
    for name in args.meshes.split(","):
        src = mesh_path(name)
        o = os.path.join(args.out, name)
        model, atlas = o + ".neuv", o + "-uv.obj"
        run([neuv, "unwrap", src, "-o", atlas, "--save-model", model, "--refine", "0", "--report", o + ".json"] + th)
        run([neuv, "unwrap", src, "-o", o + "-seed2.obj", "--seed", "2"] + th)
        faces = json.load(open(o + ".json"))["faces"]
        targets = []
        for k in SCALES:
            t = "%s-%gx" % (o, k)
            run([neuv, "remesh", src, "--faces", str(int(round(k * faces))), "-o", t + ".obj", "--quiet"])
            run([neuv, "remesh", t + ".obj", "--jitter", "-o", t + "j.obj", "--quiet"])
            targets += [("%gx" % k, t + ".obj"), ("%gx-jit" % k, t + "j.obj")]
        for label, t in targets:
            for kind, extra in (("model", []), ("lscm", ["--lscm-baseline"])):
                res = t[:-4] + "-" + kind
                times = []
                for _ in range(args.runs):
                    _, dt = run([neuv, "unwrap", t, "--model", model, "-o", res + ".obj", "--report", res + ".json"]
                                + extra + th)
                    times.append(dt)
                rep = json.load(open(res + ".json"))
                c = compare(neuv, atlas, res + ".obj")
                srcs = rep.get("provenance", {}).get("sources", {})
                net = sum(v["charts"] for k2, v in srcs.items() if k2.startswith("network"))
                row = dict(mesh=name, target=label, faces=rep["faces"], map=kind, uv_mean=c["uv_distance"]["mean"],
                           uv_p95=c["uv_distance"]["p95"], nearest=c["uv_distance_nearest"]["mean"],
                           agree=c["chart_agreement"], agree_f=c["chart_agreement_facing"],
                           past=c["across_seam"], flips=c["b_flipped"],
                           overlap=c["b_overlap_fraction"], moved=rep["model"]["moved_charts"],
                           net="%d/%d" % (net, rep["charts"]), qce=c["b_qce_mean"],
                           apply_s=statistics.median(times))
                rows.append(row)
                print("%-10s %-8s %6d %-6s %9.2e %9.2e %9.2e %7.4f %7.4f %6.3f %5d %8.2g %5d %7s %7.4f %7.2f" % tuple(
                    row[k2] for k2 in ("mesh", "target", "faces", "map", "uv_mean", "uv_p95", "nearest", "agree", "agree_f",
                                       "past", "flips", "overlap", "moved", "net", "qce", "apply_s")), flush=True)
        c = compare(neuv, atlas, o + "-seed2.obj")
        row = dict(mesh=name, target="source", faces=c["faces_b"], map="indep", uv_mean=c["uv_distance"]["mean"],
                   uv_p95=c["uv_distance"]["p95"], nearest=c["uv_distance_nearest"]["mean"], agree=c["chart_agreement"],
                   agree_f=c["chart_agreement_facing"], past=c["across_seam"], flips=c["b_flipped"],
                   overlap=c["b_overlap_fraction"], qce=c["b_qce_mean"])
        rows.append(row)
        print("%-10s %-8s %6d %-6s %9.2e %9.2e %9.2e %7.4f %7.4f %6.3f %5d %8.2g %5s %7s %7.4f %7s" % (
            name, "seed 2", row["faces"], "indep", row["uv_mean"], row["uv_p95"], row["nearest"], row["agree"], row["agree_f"],
            row["past"], row["flips"], row["overlap"], "-", "-", row["qce"], "-"), flush=True)
    json.dump(rows, open(os.path.join(args.out, "rows.json"), "w"), indent=1)


if __name__ == "__main__":
    main()
