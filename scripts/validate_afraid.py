#!/usr/bin/env python3
"""Multi-world validation of the afraid learner (M3).

For each world and seed: simulate slow laps with people stepping out of doors
(risknav-simulate), learn the afraid map from the rawlog (risknav-afraid-learn,
MCL on the map the robot was given), and compare with the simulator's truth:

- relevant emergences: door pedestrians that entered the robot's stopping
  corridor while it moved (the simulator's `enter_corridor` events);
- events matched one to one to them by time (|dt| <= MATCH_DT) and place (the
  unexpected obstacle within MATCH_DIST of the person when they entered);
- recall = matched / relevant; false events = events matched to none;
- zones per door (a zone whose rectangle comes within ZONE_DOOR_DIST of the
  door segment), false zones (near no door);
- the same zones from 3 laps and from 10 (seed 1 of each world).

Usage: python3 scripts/validate_afraid.py [--seeds 5] [--jobs 2] [--out out/validation]
Needs the built apps (scripts/build.sh). Writes summary.md and summary.json.
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
BIN = os.path.join(ROOT, "build", "bin")

MATCH_DT = 3.0          # [s]
MATCH_DIST = 1.5        # [m]
ZONE_DOOR_DIST = 1.5    # [m]

# world name -> (world config, afraid-learn config)
WORLDS = {
    "corridor-doors": ("datasets/corridor-doors/world.ini", "datasets/corridor-doors/afraid.ini"),
    "narrow_doors": ("datasets/validation/narrow_doors.ini", "datasets/validation/afraid_narrow_doors.ini"),
    "t_junction": ("datasets/validation/t_junction.ini", "datasets/validation/afraid_t_junction.ini"),
    "furnished_room": ("datasets/validation/furnished_room.ini", "datasets/validation/afraid_furnished_room.ini"),
}


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(cmd) + "\n" + r.stderr)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def doors_of(world_ini):
    """Door segments [(name, x1, y1, x2, y2)] from the world config."""
    doors, sec = [], None
    with open(os.path.join(ROOT, world_ini)) as f:
        for line in f:
            line = line.split("//")[0].strip()
            if line.startswith("["):
                sec = line.strip("[]")
            elif sec and sec.startswith("DoorPedestrian") and line.startswith("door"):
                v = [float(x) for x in line.split("=", 1)[1].split()]
                doors.append((sec, *v))
    return doors


def seg_rect_dist(seg, rect):
    """Distance between a segment and an axis-aligned rectangle (0 if they touch)."""
    x1, y1, x2, y2 = seg
    xmin, xmax, ymin, ymax = rect
    best = float("inf")
    for k in range(21):
        px, py = x1 + (x2 - x1) * k / 20, y1 + (y2 - y1) * k / 20
        dx = max(xmin - px, 0, px - xmax)
        dy = max(ymin - py, 0, py - ymax)
        best = min(best, math.hypot(dx, dy))
    return best


def one_run(world, seed, laps, out, no_doors=False):
    world_ini, afraid_ini = WORLDS[world]
    tag = f"laps{laps}" + ("-nodoors" if no_doors else "")
    sim = os.path.join(out, world, tag, f"seed{seed}", "sim")
    learn = os.path.join(out, world, tag, f"seed{seed}", "learn")
    quiet = []
    if no_doors:  # nobody steps out of a door: walkers, walls, dead ends only
        quiet = [x for d in doors_of(world_ini)
                 for x in ("--set", f"{d[0]}.trigger_probability=0")]
    run([os.path.join(BIN, "risknav-simulate"), "-q", "-o", sim, "--seed", str(seed),
         "--set", f"Route.laps={laps}", *quiet, os.path.join(ROOT, world_ini)])
    run([os.path.join(BIN, "risknav-afraid-learn"), "-q", "-o", learn,
         "--set", f"AfraidLearn.rawlogs={sim}/simulation.rawlog",
         "--set", f"AfraidLearn.groundtruth_file={sim}/groundtruth.txt",
         os.path.join(ROOT, afraid_ini)])

    agents = read_csv(os.path.join(sim, "agent_events.csv"))
    relevant = [a for a in agents if a["kind"] == "enter_corridor"]
    emerged = [a for a in agents if a["kind"] == "emerge"]
    events = read_csv(os.path.join(learn, "events.csv"))
    zones = read_csv(os.path.join(learn, "zones.csv"))

    # One-to-one matching, closest in time first.
    pairs = []
    for i, e in enumerate(events):
        ex = float(e["obstacle_x"]) if e["obstacle_x"] not in ("", "nan") else float(e["robot_x"])
        ey = float(e["obstacle_y"]) if e["obstacle_y"] not in ("", "nan") else float(e["robot_y"])
        for j, a in enumerate(relevant):
            dt = abs(float(e["t"]) - float(a["t"]))
            d = math.hypot(ex - float(a["x"]), ey - float(a["y"]))
            if dt <= MATCH_DT and d <= MATCH_DIST:
                pairs.append((dt, i, j))
    used_e, used_a = set(), set()
    for dt, i, j in sorted(pairs):
        if i not in used_e and j not in used_a:
            used_e.add(i)
            used_a.add(j)
    doors = doors_of(world_ini)
    door_zones = {d[0]: 0 for d in doors}
    false_zones = 0
    for z in zones:
        rect = (float(z["x_min"]), float(z["x_max"]), float(z["y_min"]), float(z["y_max"]))
        near = [d[0] for d in doors if seg_rect_dist(d[1:], rect) <= ZONE_DOOR_DIST]
        for n in near:
            door_zones[n] += 1
        if not near:
            false_zones += 1
    s = json.load(open(os.path.join(learn, "summary.json")))
    return {
        "world": world, "seed": seed, "laps": laps, "no_doors": no_doors,
        "emergences": len(emerged), "relevant": len(relevant),
        "events": len(events), "matched": len(used_a),
        "false_events": len(events) - len(used_e),
        "zones": len(zones), "false_zones": false_zones,
        "doors": len(doors), "doors_with_zone": sum(1 for v in door_zones.values() if v),
        "doors_zoned": sorted(k for k, v in door_zones.items() if v),
        "mcl_error_mean_m": s["localization"].get("mcl_error_mean_m"),
        "status": s["status"],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "validation"))
    ap.add_argument("--worlds", default=",".join(WORLDS))
    args = ap.parse_args()
    worlds = args.worlds.split(",")
    jobs = [(w, s, 3, False) for w in worlds for s in range(1, args.seeds + 1)]
    jobs += [(w, 1, 10, False) for w in worlds]
    jobs += [(w, 1, 3, True) for w in worlds]
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        futs = {ex.submit(one_run, w, s, l, args.out, nd): (w, s, l, nd)
                for w, s, l, nd in jobs}
        for f in concurrent.futures.as_completed(futs):
            try:
                results.append(f.result())
            except RuntimeError as e:
                print("FAILED:", futs[f], e, file=sys.stderr)
                results.append({"world": futs[f][0], "seed": futs[f][1], "laps": futs[f][2],
                                "no_doors": futs[f][3], "failed": str(e).splitlines()[-1]})
    results.sort(key=lambda r: (r["world"], r["no_doors"], r["laps"], r["seed"]))
    os.makedirs(args.out, exist_ok=True)
    json.dump(results, open(os.path.join(args.out, "summary.json"), "w"), indent=1)

    lines = ["| world | seeds | relevant emergences | matched events | recall | false events | "
             "doors with a zone (every seed) | false zones | 10 laps: same doors, false zones "
             "| no door pedestrians: events, zones |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for w in worlds:
        ok = [r for r in results if r["world"] == w and "failed" not in r]
        rs = [r for r in ok if r["laps"] == 3 and not r["no_doors"]]
        failed = [r for r in results if r["world"] == w and "failed" in r]
        ten = [r for r in ok if r["laps"] == 10]
        quiet = [r for r in ok if r["no_doors"]]
        nodoors = f"{quiet[0]['events']}, {quiet[0]['zones']}" if quiet else "n/a"
        rel = sum(r["relevant"] for r in rs)
        mat = sum(r["matched"] for r in rs)
        fe = sum(r["false_events"] for r in rs)
        every = sum(1 for r in rs if r["doors_with_zone"] == r["doors"])
        fz = sum(r["false_zones"] for r in rs)
        three = next((r for r in rs if r["seed"] == 1), None)
        same = "n/a"
        if ten and three:
            same = ("yes" if ten[0]["doors_zoned"] == three["doors_zoned"] else
                    f"no ({three['doors_zoned']} vs {ten[0]['doors_zoned']})")
            same += f", {ten[0]['false_zones']}"
        lines.append(f"| {w} | {len(rs)}{' (' + str(len(failed)) + ' failed)' if failed else ''} "
                     f"| {rel} | {mat} | {100.0 * mat / rel if rel else float('nan'):.0f} % "
                     f"| {fe} | {every}/{len(rs)} | {fz} | {same} | {nodoors} |")
    table = "\n".join(lines)
    open(os.path.join(args.out, "summary.md"), "w").write(table + "\n")
    print(table)
    for r in results:
        print(json.dumps(r))


if __name__ == "__main__":
    main()
