#!/usr/bin/env python3
"""The viewpoint planner (M4) on every landmark map and both robots of
Yamashita et al. 004 (R1: 1 px, 10 %; R2: 3 px, 15 %): per S the chosen path
(shortest feasible, then fewest viewpoints), the optimal plan, how often the
three-landmark observation is chosen where it is available, and the Monte
Carlo check of the worst-case bounds. Prints markdown (the README's tables).

  python3 scripts/validate_viewpoint.py [--bin build/bin/risknav-viewpoint-plan]
"""
import argparse, csv, json, os, subprocess, sys, tempfile, time
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAPS = ["landmarks-two-routes", "landmarks-pillars", "landmarks-corridor"]


def run(binary, ini, out):
    t = time.time()
    r = subprocess.run([binary, "-q", "-o", out, ini], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s failed: %s" % (ini, r.stderr.strip()))
    return json.load(open(os.path.join(out, "summary.json"))), time.time() - t


def strategy_use(out):
    vp = defaultdict(dict)
    for row in csv.DictReader(open(os.path.join(out, "strategies.csv"))):
        vp[row["viewpoint"]][row["strategy"]] = row
    avail = sum(1 for d in vp.values() if "C" in d)
    chosen = sum(1 for d in vp.values() if "C" in d and d["C"]["chosen"] == "true")
    return len(vp), avail, chosen


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "build/bin/risknav-viewpoint-plan"))
    a = ap.parse_args()
    tmp = tempfile.mkdtemp()
    summary = []
    for m in MAPS:
        print("\n#### %s\n" % m)
        res = {}
        for r in ["r1", "r2"]:
            out = os.path.join(tmp, m + "-" + r)
            res[r] = run(a.bin, os.path.join(ROOT, "datasets", m, r + ".ini"), out) + (out,)
        print("| S [mm] | R1: route, length [mm], viewpoints | R2: route, length [mm], viewpoints |")
        print("|---:|---|---|")
        for k, sp in enumerate(res["r1"][0]["sweep"]):
            cells = []
            for r in ["r1", "r2"]:
                s = res[r][0]["sweep"][k]
                feas = [p for p in s["paths"] if p["feasible"]]
                if not feas:
                    cells.append("infeasible" + (" (%s)" % s["note"] if s["note"] else ""))
                    continue
                b = min(feas, key=lambda p: (round(p["length_m"], 3), p["viewpoints"]))
                o = res[r][0]["optimal"]
                star = "**" if o and o["S"] == s["S"] and o["path"] == b["path"] else ""
                cells.append("%s%d, %.0f, %d%s" % (star, b["route"], b["length_m"] * 1000,
                                                    b["viewpoints"], star))
            print("| %.0f | %s | %s |" % (sp["S"] * 1000, cells[0], cells[1]))
        for r in ["r1", "r2"]:
            s, secs, out = res[r]
            o = s["optimal"]
            n, avail, chosen = strategy_use(out) if o else (0, 0, 0)
            mc = s["monte_carlo"]
            paths = sum(len(x["paths"]) for x in s["sweep"])
            feas = sum(1 for x in s["sweep"] for p in x["paths"] if p["feasible"])
            summary.append((m, r.upper(), o, n, avail, chosen, mc, paths, feas, s["routes"],
                            s["timing"]["plan_s"]))
    print("\n| map | robot | optimal: S, route, length, viewpoints (A/B/C) | C chosen / available at its viewpoints | feasible (S, path) / all | routes | Monte Carlo: draws, max error / bound | plan time |")
    print("|---|---|---|---|---|---|---|---|")
    for (m, r, o, n, avail, chosen, mc, paths, feas, routes, secs) in summary:
        opt = ("%.0f mm, %d, %.0f mm, %d (%d/%d/%d)" % (o["S"] * 1000, o["route"], o["length_m"] * 1000,
               o["viewpoints"], o["strategies"]["A"], o["strategies"]["B"], o["strategies"]["C"])
               if o else "none")
        print("| %s | %s | %s | %d / %d | %d / %d | %d | %d, %.3f | %.2f s |" % (
            m, r, opt, chosen, avail, feas, paths, routes, mc["draws"], mc["max_ratio_total"], secs))


if __name__ == "__main__":
    main()
