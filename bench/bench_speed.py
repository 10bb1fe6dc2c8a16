#!/usr/bin/env python3
"""bench/speed: where `neuv unwrap` spends its time, mesh by mesh (issue 16, item 5).

For each mesh (default: every mesh in ../shared/meshes), runs `neuv unwrap`
with default options and with `--method lscm` (the same charts flattened by
LSCM, no parameterization networks), RUNS times each, the two alternating,
and prints the report's per-stage seconds of the default run (medians; with
a simplified training copy the copy's stages are summed into the same
columns and its simplification is "simplify"), its total, LSCM's total, and
their ratio: how much of the run the networks cost over a classic map on
the same pipeline. Wall seconds of the whole process are the report's
seconds.total plus the process start (a few ms).

usage: bench/bench_speed.py [--neuv build/neuv] [--shared ../shared] [--threads 2]
                            [--runs 1] [--meshes spot.obj,cow.obj] [--json-out rows.json]
"""
import argparse, json, os, statistics, subprocess, sys, tempfile

STAGES = ["simplify", "operators", "patches", "param", "repair", "pack", "metrics"]


def run(neuv, mesh, extra, threads, out):
    report = os.path.join(out, "r.json")
    cmd = [neuv, "unwrap", mesh, "-o", os.path.join(out, "o.obj"), "--report", report, "--threads", threads,
           "--quiet"] + extra
    subprocess.run(cmd, check=True)
    r = json.load(open(report))
    sec = r["seconds"]
    stages = {k: sec.get(k, 0.0) for k in STAGES}
    copy = sec.get("copy")
    if copy:
        for k in STAGES:
            stages[k] += copy.get(k, 0.0)
        stages["simplify"] = copy.get("simplify", 0.0)
    # Loading, cleaning and export: what the stages above leave of the total.
    stages["other"] = sec["total"] - sum(stages[k] for k in STAGES)
    stages["split"] = r["pack"].get("split_seconds", 0.0)
    return {"faces": r["faces"], "charts": r["charts"], "copy": (r.get("model") or {}).get("train_faces"),
            "total": sec["total"], "stages": stages}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--neuv", default="build/neuv")
    ap.add_argument("--shared", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared"))
    ap.add_argument("--threads", default="2")
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--meshes", default="")
    ap.add_argument("--json-out", default="")
    a = ap.parse_args()
    folder = os.path.join(a.shared, "meshes")
    if a.meshes:
        names = a.meshes.split(",")
    elif os.path.isdir(folder):
        names = sorted(f for f in os.listdir(folder) if f.endswith((".obj", ".off", ".ply", ".stl", ".glb", ".gltf")))
    else:
        print(f"bench_speed: no {folder}", file=sys.stderr)
        return 77
    shown = ["simplify", "operators", "patches", "param", "repair", "pack", "split", "metrics", "other"]
    title = {"split": "of which split trials s"}
    print("| mesh | faces | trained on | charts | " + " | ".join(title.get(c, f"{c} s") for c in shown) +
          " | total s | --method lscm s | ratio |")
    print("|---|---:|---:|---:|" + "---:|" * len(shown) + "---:|---:|---:|")
    rows = []
    with tempfile.TemporaryDirectory() as out:
        for name in names:
            mesh = name if os.path.isabs(name) else os.path.join(folder, name)
            d, l = [], []
            for _ in range(a.runs):
                d.append(run(a.neuv, mesh, [], a.threads, out))
                l.append(run(a.neuv, mesh, ["--method", "lscm"], a.threads, out))
            med = {c: statistics.median(x["stages"][c] for x in d) for c in shown}
            total = statistics.median(x["total"] for x in d)
            lscm = statistics.median(x["total"] for x in l)
            first = d[0]
            copy = first["copy"] if first["copy"] else first["faces"]
            print(f"| {os.path.basename(mesh)} | {first['faces']} | {copy} | {first['charts']} | " +
                  " | ".join(f"{med[c]:.2f}" for c in shown) +
                  f" | {total:.2f} | {lscm:.2f} | {total / lscm:.1f} |", flush=True)
            rows.append({"mesh": os.path.basename(mesh), "faces": first["faces"], "trained_on": copy,
                         "charts": first["charts"], "stages": med, "total": total, "lscm_total": lscm})
    if rows:
        tot = sum(r["total"] for r in rows)
        lt = sum(r["lscm_total"] for r in rows)
        print(f"\n{len(rows)} meshes: {tot:.1f} s in all, {lt:.1f} s with --method lscm (ratio {tot / lt:.1f}); "
              f"median ratio {statistics.median(r['total'] / r['lscm_total'] for r in rows):.1f}")
    if a.json_out:
        json.dump(rows, open(a.json_out, "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
