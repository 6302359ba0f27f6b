#!/usr/bin/env python3
"""Multi-world, multi-seed validation of risknav-explore (M1).

Runs the adaptive mode on:
- the office (datasets/office/explore.ini), people off;
- the office with the corridor walker of datasets/office/world.ini added;
- the T junction (datasets/validation/explore_t_junction.ini) and four
  worlds drawn by someone who had not seen the code (a U corridor, a hall with pillars, rooms
  with a dead-end room, the same with a destination behind it), none of which
  the controller was tuned on;
each over seeds 1..N, and prints per world: runs with every destination
reached (judged on the true pose: within goal_tolerance where the robot
believed it had arrived), runs where the robot believed it had arrived at
every destination (the speed controller's own result: M1 does not localize,
its belief is odometry), collisions, near misses, time (mean and range), min
clearance, the largest belief error at an arrival, and each destination not
reached with its status (localization_error: the belief arrived, the truth is
out of tolerance; unreachable: given up; not_reached: out of time) and its
true and belief errors. Extra `--set` options apply to every run (e.g.
`--set Explore.ego_motion=ground_truth`). Exits 1 if any run collides or
misses a destination in truth.

Usage: python3 scripts/validate_explore.py [--seeds 5] [--jobs 2]
       [--out out/validate-explore] [--set Section.key=value ...]
Needs the built apps (scripts/build.sh). Writes summary.md and summary.json.
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
APP = os.path.join(ROOT, "build", "bin", "risknav-explore")


def walker_config(out):
    """The office config with [CorridorWalker1] of the office world added."""
    office = os.path.join(ROOT, "datasets", "office")
    text = open(os.path.join(office, "explore.ini")).read()
    text = text.replace("office.png", os.path.join(office, "office.png"))
    world = open(os.path.join(office, "world.ini")).read().splitlines()
    start = world.index("[CorridorWalker1]")
    section = []
    for line in world[start:]:
        if not line.strip() and section:
            break
        section.append(line)
    path = os.path.join(out, "office_walker.ini")
    with open(path, "w") as f:
        f.write(text + "\n" + "\n".join(section) + "\n")
    return path


def run(args):
    name, config, seed, out, sets = args
    d = os.path.join(out, "%s-%d" % (name, seed))
    cmd = [APP, config, "--out", d, "--seed", str(seed), "-q",
           "--set", "Explore.modes=adaptive"]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s seed %d: exit %d: %s" % (name, seed, r.returncode, r.stderr))
    m = json.load(open(os.path.join(d, "summary.json")))["modes"][0]
    return name, seed, m


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--out", default=os.path.join(ROOT, "out", "validate-explore"))
    p.add_argument("--set", action="append", default=[], dest="sets")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    worlds = [
        ("office", os.path.join(ROOT, "datasets", "office", "explore.ini")),
        ("office_walker", walker_config(a.out)),
    ] + [(w, os.path.join(ROOT, "datasets", "validation", "explore_%s.ini" % w))
         for w in ("t_junction", "u_corridor", "hall", "rooms", "rooms_trap")]
    jobs = [(n, c, s, a.out, a.sets) for n, c in worlds
            for s in range(1, a.seeds + 1)]
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
        results = list(ex.map(run, jobs))
    rows, summary = [], {}
    # where the robot believed it had arrived (judged on the truth after)
    arrived = ("reached", "localization_error", "fell_short")

    def missed(s, k, m):
        st = m["destinations"][k]
        text = "seed %d D%d %s" % (s, k + 1, st)
        true_e = (m.get("destination_error_m") or [None] * (k + 1))[k]
        belief_e = (m.get("destination_belief_error_m") or [None] * (k + 1))[k]
        if true_e is not None and belief_e is not None:
            text += " (%.2f m off, belief %.2f m off)" % (true_e, belief_e)
        return text

    for name, _ in worlds:
        ms = [(s, m) for n, s, m in results if n == name]
        times = [m["time_s"] for _, m in ms]
        not_reached = [missed(s, k, m) for s, m in ms
                       for k, st in enumerate(m["destinations"]) if st != "reached"]
        belief = [e for _, m in ms for e in m.get("destination_belief_error_m", [])
                  if e is not None]
        w = {
            "runs": len(ms),
            "all_reached": sum(1 for _, m in ms if m["all_reached"]),
            "all_arrived_in_belief": sum(
                1 for _, m in ms if all(st in arrived for st in m["destinations"])),
            "localization_errors": sum(m["destinations"].count("localization_error")
                                       for _, m in ms),
            "max_belief_error_m": max(belief) if belief else None,
            "collisions": sum(m["collisions"] for _, m in ms),
            "near_misses": sum(m["near_misses"] for _, m in ms),
            "time_mean_s": sum(times) / len(times),
            "time_min_s": min(times),
            "time_max_s": max(times),
            "min_clearance_m": min(m["min_clearance_m"] for _, m in ms),
            "not_reached": not_reached,
        }
        summary[name] = w
        rows.append("| %s | %d/%d | %d/%d | %d | %d | %.1f s (%.1f-%.1f) | %.3f m "
                    "| %s | %s |" % (
                        name, w["all_reached"], w["runs"], w["all_arrived_in_belief"],
                        w["runs"], w["collisions"], w["near_misses"],
                        w["time_mean_s"], w["time_min_s"], w["time_max_s"],
                        w["min_clearance_m"],
                        "-" if w["max_belief_error_m"] is None
                        else "%.2f m" % w["max_belief_error_m"],
                        ", ".join(not_reached) or "-"))
    table = ["| world | all reached (true pose) | all arrived (belief) | collisions "
             "| near misses | time mean (range) | min clearance | max belief error "
             "| not reached |", "|---|---|---|---|---|---|---|---|---|"] + rows
    print("\n".join(table))
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(table) + "\n")
    with open(os.path.join(a.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    return 0 if all(w["all_reached"] == w["runs"] and w["collisions"] == 0
                    for w in summary.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
