#!/usr/bin/env python3
"""risknav's apps on public occupancy maps nobody here drew, with seeded
random start/goal pairs: success rates and every failure's reason.

For each map and seed, 12 pairs are drawn (random.Random seeded by the seed
and the map's name, so a seed gives the same pairs every time and another
seed other pairs):
  - start and goal on free cells (unknown is not free) whose clearance to any
    non-free cell (and to the outside of the map) is >= 0.5 m;
  - both in one connected component (4-connected) of the cells where the
    robot disc fits: clearance >= [Robot] radius + 0.1 m;
  - pairs 0, 3, 6, 9 (a third) "behind obstacles": the straight segment from
    start to goal crosses a non-free cell; the others are unconstrained;
  - goal >= 3 m from the start, start heading uniform in [-180, 180) deg.
Clearance is measured as the apps measure it: from the cell's centre to the
nearest non-free cell's square. Cells are classified with the base config's
[World] rule (occupancy = 1 - P(free) >= occupied_threshold: obstacle, <=
free_threshold: free, between: unknown), P(free) as MRPT stores it (8-bit
log-odds). ROS map YAML (+ PGM / PNG), plain PGM / PNG bitmaps and MRPT
.gridmap(.gz) are read here (and match, cell for cell, the grid the apps
build from them); any other format (.simplemap) is read by the app:
risknav-simulate on a two-point route at (0.01, 0.01), every cell counted
passable for that run, writes the grid it built (map.gridmap.gz); a map that
does not hold that point is reported as not usable.

Each pair is then run:
  navigate  risknav-navigate on config/validate_maps_navigate.ini (no people,
            no clutter, CStoppingDistanceLimiter; the map known)
  m1        risknav-navigate on datasets/office/navigate_m1.ini without its
            boxes (CAdaptiveSpeedLimiter: the map unknown to the robot)
  explore   risknav-explore on datasets/office/explore.ini without its boxes,
            the pair's goal as the one destination, modes = adaptive
  risk-eval risknav-risk-eval with the pair's start and goal and the app's
            defaults (3 GVG routes, 3 grid ways of distinct classes, the
            navigate config's [Robot] radius): "reached" = a route found
            (status ok: the best row is not excluded, its U finite)
with --set World.map_file, the start, the goal and duration_max
= 60 s + 4 x the way's length / [Robot] max_v, and --seed SEED.
The way's length is the shortest 8-connected way (A*) over the cells where
the disc fits, on the true map: the budget a robot that knew the map would
need four times over, whatever it knows.
--planner P adds --set Navigate.global_planner=P (without it nothing is
passed); --localization mcl adds --set Navigate.localization=mcl: MRPT's
MCL on the laser and the map, its particles drawn around the start as
[Localization] says (the app's defaults: a +-1 m box, any heading, 5000
particles; change with --set Localization.init_xy=... etc.).
A run has reached its goal when its TRUE final pose (summary.json end_pose;
explore: the last row of cycles.csv) lies within the config's goal_tolerance;
the belief's error is reported beside. A run fails when it did not reach,
collided, or its app did not exit 0 (exit 2 on a pair drawn as valid is a
failure: the app refused what this script thinks is valid input).

Usage:
  python3 scripts/validate_maps.py [--seed N | --seeds 1,2,3] [--maps a,b | none]
      [--map-file PATH ...] [--mode navigate|m1|explore|risk-eval]
      [--planner grid|risk|none] [--localization ground_truth|mcl]
      [--jobs 2] [--out DIR] [--pairs 12] [--set SECTION.KEY=V ...]
      [--list] [--dry-run]
Prints a markdown table (one row per map and an overall row) and every
failure; writes DIR/results.json (pairs, runs, per-map figures). Progress on
stderr. Exit status 0 when the runs were made (whatever they gave), 2 on bad
usage. Env RISKNAV_NAVIGATE / RISKNAV_EXPLORE / RISKNAV_SIMULATE /
RISKNAV_RISK_EVAL: other builds of the apps.
"""
import argparse
import collections
import concurrent.futures
import configparser
import gzip
import heapq
import json
import math
import os
import random
import re
import struct
import subprocess
import sys
import threading
import time
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "bin")
APPS = {
    "navigate": os.environ.get("RISKNAV_NAVIGATE", os.path.join(BIN, "risknav-navigate")),
    "explore": os.environ.get("RISKNAV_EXPLORE", os.path.join(BIN, "risknav-explore")),
    "simulate": os.environ.get("RISKNAV_SIMULATE", os.path.join(BIN, "risknav-simulate")),
    "risk-eval": os.environ.get("RISKNAV_RISK_EVAL", os.path.join(BIN, "risknav-risk-eval")),
}
MRPT_DATASETS = "/usr/share/mrpt/datasets"

# name: (path, what it is). Paths relative to the repository's root.
MAPS = collections.OrderedDict([
    ("depot", ("datasets/maps/depot/depot.yaml", "Nav2 depot: a warehouse hall with pallet racks")),
    ("warehouse", ("datasets/maps/warehouse/warehouse.yaml", "Nav2 warehouse: aisles between long racks")),
    ("tb3_sandbox", ("datasets/maps/tb3_sandbox/tb3_sandbox.yaml", "TurtleBot3 world: a small hexagonal arena with 9 pillars")),
    ("willow", ("datasets/maps/willow/willow-full-0.05.yaml", "Willow Garage office floor (SLAM map)")),
    ("small_house", ("datasets/maps/small_house/map.yaml", "AWS RoboMaker small house: a furnished home")),
    ("bookstore", ("datasets/maps/bookstore/map.yaml", "AWS RoboMaker bookstore: a shop with shelves")),
    ("malaga_campus", (MRPT_DATASETS + "/2006-MalagaCampus.gridmap.gz", "MRPT: Malaga campus (outdoor SLAM grid)")),
    ("localization_demo", (MRPT_DATASETS + "/localization_demo.simplemap.gz", "MRPT: localization demo (simplemap)")),
    ("malaga_cs_fac", (MRPT_DATASETS + "/malaga-cs-fac-building.simplemap.gz", "MRPT: Malaga CS faculty building (simplemap)")),
])

BASE = {
    "navigate": "config/validate_maps_navigate.ini",
    "m1": "datasets/office/navigate_m1.ini",
    "explore": "datasets/office/explore.ini",
}

CLEAR_ENDS = 0.5          # [m] clearance of start and goal
DISC_MARGIN = 0.1         # [m] added to the robot radius for the component
MIN_DIST = 3.0            # [m] start to goal
BEHIND_EVERY = 3          # pair k with k % 3 == 0 must be behind obstacles

_print_lock = threading.Lock()


def log(msg):
    with _print_lock:
        print(msg, file=sys.stderr, flush=True)


# ----------------------------------------------------------------------------
# Config (MRPT .ini, read as risknav's configs are written: '//' and ';'
# comments after values)


def read_ini(path):
    cp = configparser.ConfigParser(inline_comment_prefixes=("//", ";"), strict=False,
                                   interpolation=None, comment_prefixes=(";", "#"))
    cp.optionxform = str
    with open(path) as f:
        cp.read_string(f.read(), source=path)
    return cp


def ini_get(cp, sec, key, default):
    try:
        v = cp[sec][key].strip()
        return v if v != "" else default
    except KeyError:
        return default


def strip_sections(text, prefixes):
    """The config text without the sections whose name starts with one of
    `prefixes` (the office's boxes and walkers belong to the office)."""
    out, skip = [], False
    for line in text.splitlines(keepends=True):
        m = re.match(r"\s*\[([^\]]+)\]", line)
        if m:
            skip = m.group(1).startswith(prefixes)
        if not skip:
            out.append(line)
    return "".join(out)


# ----------------------------------------------------------------------------
# MRPT's 8-bit log-odds cells: what P(free) a map's pixel becomes


def _l2p(l):
    if l < -127:
        l = -127
    return 1.0 / (1.0 + math.exp(-l / 16.0))


def _p2l(p):
    j = int(p * 127)
    j = min(max(j, 0), 127)
    q = min(1.0 - 1e-14, max(1e-14, j / 127.0))
    x = (math.log(q) - math.log(1 - q)) * 16
    L = int(math.copysign(math.floor(abs(x) + 0.5), x))  # C's round(): half away from 0
    return min(max(L, -127), 127)


def stored_pfree(p):
    """P(free) after MRPT's setCell() and getCell() (8-bit log-odds)."""
    return _l2p(_p2l(p))


# ----------------------------------------------------------------------------
# Images: PGM (P2/P5) and PNG (any standard colour type, 1-16 bits), read as
# OpenCV's IMREAD_GRAYSCALE does (8 bits; colour: 0.299 R + 0.587 G + 0.114 B)


def read_pgm(path):
    with open(path, "rb") as f:
        data = f.read()
    magic = data[:2]
    if magic not in (b"P5", b"P2"):
        raise ValueError(f"{path}: not a PGM (P2/P5)")
    vals, i = [], 2
    while len(vals) < 3:
        while data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            while data[i:i + 1] not in (b"\n", b"\r", b""):
                i += 1
            continue
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        vals.append(int(data[i:j]))
        i = j
    w, h, maxv = vals
    i += 1  # one whitespace after maxval
    if magic == b"P5":
        if maxv < 256:
            px = data[i:i + w * h]
            if maxv != 255:
                px = bytes(min(255, (v * 255 + maxv // 2) // maxv) for v in px)
        else:
            raw = data[i:i + 2 * w * h]
            px = bytes(min(255, (((raw[2 * k] << 8) | raw[2 * k + 1]) * 255 + maxv // 2) // maxv)
                       for k in range(w * h))
    else:
        nums = [int(t) for t in data[i:].split()][:w * h]
        px = bytes(min(255, (v * 255 + maxv // 2) // maxv) for v in nums)
    if len(px) != w * h:
        raise ValueError(f"{path}: truncated PGM")
    return w, h, px


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    i, idat, plte, trns = 8, [], None, None
    w = h = depth = ctype = interlace = None
    while i < len(data):
        n, typ = struct.unpack(">I4s", data[i:i + 8])
        chunk = data[i + 8:i + 8 + n]
        i += 12 + n
        if typ == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
        elif typ == b"PLTE":
            plte = chunk
        elif typ == b"IDAT":
            idat.append(chunk)
        elif typ == b"IEND":
            break
    if interlace:
        raise ValueError(f"{path}: interlaced PNG not read here")
    ch = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[ctype]
    bpp = max(1, ch * depth // 8)
    stride = (w * ch * depth + 7) // 8
    raw = zlib.decompress(b"".join(idat))
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if ft == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif ft == 2:
            for x in range(stride):
                line[x] = (line[x] + prev[x]) & 255
        elif ft == 3:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + ((a + prev[x]) >> 1)) & 255
        elif ft == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                b, c = prev[x], prev[x - bpp] if x >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pr) & 255
        rows.append(bytes(line))
        prev = line
    out = bytearray(w * h)

    def samples(line):
        if depth == 8:
            return line
        if depth == 16:
            return bytes(line[k] for k in range(0, len(line), 2))
        per = 8 // depth
        mask = (1 << depth) - 1
        vals = []
        for byte in line:
            for s in range(per):
                vals.append((byte >> (8 - depth * (s + 1))) & mask)
        return vals

    for y, line in enumerate(rows):
        s = samples(line)
        for x in range(w):
            if ctype == 0:
                v = s[x]
                if depth < 8:
                    v = v * 255 // ((1 << depth) - 1)
            elif ctype == 3:
                k = s[x]
                r, g, b = plte[3 * k:3 * k + 3]
                v = int(0.299 * r + 0.587 * g + 0.114 * b + 0.5)
            elif ctype == 4:
                v = s[2 * x]
            else:
                r, g, b = s[ch * x], s[ch * x + 1], s[ch * x + 2]
                v = int(0.299 * r + 0.587 * g + 0.114 * b + 0.5)
            out[y * w + x] = v
    return w, h, bytes(out)


def read_image(path):
    with open(path, "rb") as f:
        head = f.read(8)
    if head[:2] in (b"P5", b"P2"):
        return read_pgm(path)
    if head == b"\x89PNG\r\n\x1a\n":
        return read_png(path)
    raise ValueError(f"{path}: image format not read by this script")


def parse_map_yaml(path):
    """ROS map_server YAML: flat key: value lines, origin a [x, y, yaw] list."""
    kv = {}
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line or ":" not in line:
                continue
            k, v = line.split(":", 1)
            kv[k.strip()] = v.strip().strip("'\"")
    o = [float(t) for t in kv["origin"].strip("[]").split(",")]
    img = kv["image"]
    if not os.path.isabs(img):
        img = os.path.join(os.path.dirname(path), img)
    return {
        "image": img, "resolution": float(kv["resolution"]), "origin": o,
        "negate": kv.get("negate", "0") in ("1", "true"),
        "occupied_thresh": float(kv.get("occupied_thresh", 0.65)),
        "free_thresh": float(kv.get("free_thresh", 0.196)),
        "mode": kv.get("mode", "trinary"),
    }


# ----------------------------------------------------------------------------
# The grid: nonfree[cy * nx + cx] (cy = 0 at the bottom), cell centres at
# x0 + (cx + 0.5) res, y0 + (cy + 0.5) res


def _f32(v):
    return struct.unpack("<f", struct.pack("<f", v))[0]


def mrpt_min_bound(v, res):
    """MRPT's COccupancyGridMap2D::setSize() moves the lower bounds onto a
    whole number of cells (res * round(v / res), in float): a map whose
    origin is not a multiple of its resolution lies up to half a cell away
    from where its YAML puts it, in every risknav app."""
    q = _f32(_f32(v) / _f32(res))
    return _f32(_f32(res) * math.copysign(math.floor(abs(q) + 0.5), q))


class Grid:
    def __init__(self, nx, ny, res, x0, y0, nonfree, source):
        self.nx, self.ny, self.res = nx, ny, res
        self.x0, self.y0 = mrpt_min_bound(x0, res), mrpt_min_bound(y0, res)
        self.shift = (self.x0 - x0, self.y0 - y0)
        self.nonfree = nonfree  # bytearray, 1 = obstacle or unknown
        self.source = source

    def centre(self, i):
        cy, cx = divmod(i, self.nx)
        return self.x0 + (cx + 0.5) * self.res, self.y0 + (cy + 0.5) * self.res

    def cell(self, x, y):
        cx = math.floor((x - self.x0) / self.res)
        cy = math.floor((y - self.y0) / self.res)
        if 0 <= cx < self.nx and 0 <= cy < self.ny:
            return cy * self.nx + cx
        return None


def classify(pfree_by_value, world):
    """A 256-entry table: pixel/cell value -> 1 when not free."""
    free_thr = world["free_threshold"]
    return bytes(0 if (1.0 - p) <= free_thr else 1 for p in pfree_by_value)


def grid_from_image(w, h, px, res, x0, y0, pfree_of_grey, world, source):
    table = classify([stored_pfree(pfree_of_grey(g)) for g in range(256)], world)
    nonfree = bytearray(w * h)
    for cy in range(h):
        row = h - 1 - cy  # image row 0 is the top
        nonfree[cy * w:(cy + 1) * w] = px[row * w:(row + 1) * w].translate(table)
    return Grid(w, h, res, x0, y0, nonfree, source)


def grid_from_gridmap(path, world, source=None):
    data = gzip.open(path).read() if path.endswith(".gz") else open(path, "rb").read()
    old = not (data[0] & 0x80)
    nlen = struct.unpack("<I", data[0:4])[0] if old else data[0] & 0x7F
    o = (4 if old else 1) + nlen
    name = data[(4 if old else 1):o].decode("latin1")
    if not name.endswith("COccupancyGridMap2D"):
        raise ValueError(f"{path}: not an MRPT COccupancyGridMap2D ({name!r})")
    version = struct.unpack("<I", data[o:o + 4])[0] if old else data[o]
    o += 4 if old else 1
    bits = 8
    if version >= 2:
        bits = data[o]
        o += 1
    sx, sy = struct.unpack("<II", data[o:o + 8])
    x0, x1, y0, y1, res = struct.unpack("<5f", data[o + 8:o + 28])
    o += 28
    n = sx * sy
    if bits == 8:
        cells = data[o:o + n]
    else:
        cells = data[o + 1:o + 2 * n:2]  # MRPT keeps the high byte
    if len(cells) != n:
        raise ValueError(f"{path}: truncated")
    if version < 3:
        pf = [stored_pfree(v / 255.0) for v in range(256)]
    else:
        pf = [_l2p(v - 256 if v > 127 else v) for v in range(256)]
    nonfree = bytearray(cells.translate(classify(pf, world)))
    return Grid(sx, sy, res, x0, y0, nonfree, source or path)


def grid_from_app(path, world, cfg_world, workdir):
    """The grid the apps build from `path` (e.g. a .simplemap): written by
    risknav-simulate on a one-point route at the origin, with every cell
    counted as passable for that one run."""
    os.makedirs(workdir, exist_ok=True)
    ini = os.path.join(workdir, "probe.ini")
    lines = ["[World]", f"map_file = {os.path.abspath(path)}"]
    for k in ("map_resolution", "map_origin_x", "map_origin_y", "simplemap_resolution"):
        if k in cfg_world:
            lines.append(f"{k} = {cfg_world[k]}")
    lines += ["occupied_threshold = 1", "unknown_is_obstacle = false",
              "outside_is_obstacle = false",
              "[Route]", "waypoints = 0.01 0.01 0.02 0.01", ""]
    with open(ini, "w") as f:
        f.write("\n".join(lines))
    out = os.path.join(workdir, "probe")
    r = subprocess.run([APPS["simulate"], "-q", "-o", out, ini], capture_output=True, text=True)
    if r.returncode != 0:
        raise ValueError(f"risknav-simulate could not give the grid of {path} "
                         f"(exit {r.returncode}: {r.stderr.strip()})")
    return grid_from_gridmap(os.path.join(out, "map.gridmap.gz"), world, source=path)


def load_grid(path, cfg, workdir):
    w = cfg["World"] if cfg.has_section("World") else {}
    world = {
        "occupied_threshold": float(ini_get(cfg, "World", "occupied_threshold", 0.65)),
        "free_threshold": float(ini_get(cfg, "World", "free_threshold", 0.35)),
    }
    low = path.lower()
    if low.endswith((".yaml", ".yml")):
        y = parse_map_yaml(path)
        if y["origin"][2] != 0:
            raise ValueError(f"{path}: origin yaw != 0 (the apps refuse it)")
        wd, hd, px = read_image(y["image"])

        def pf(g):
            grey = g / 255.0
            occ = grey if y["negate"] else 1.0 - grey
            if y["mode"] == "scale":
                return 1.0 - occ
            return 0.0 if occ > y["occupied_thresh"] else (1.0 if occ < y["free_thresh"] else 0.5)
        return grid_from_image(wd, hd, px, y["resolution"], y["origin"][0], y["origin"][1],
                               pf, world, path)
    if low.endswith((".gridmap", ".gridmap.gz")):
        return grid_from_gridmap(path, world)
    if low.endswith((".pgm", ".png")):
        wd, hd, px = read_image(path)
        return grid_from_image(wd, hd, px, float(ini_get(cfg, "World", "map_resolution", 0.05)),
                               float(ini_get(cfg, "World", "map_origin_x", 0)),
                               float(ini_get(cfg, "World", "map_origin_y", 0)),
                               lambda g: g / 255.0, world, path)
    return grid_from_app(path, world, dict(w), workdir)


# ----------------------------------------------------------------------------
# Clearance (centre of a cell to the nearest non-free cell's square; outside
# the map is non-free) and the robot disc's connected components


def too_close(grid, r):
    """bytearray: 1 where a cell is non-free or its clearance is < r."""
    nx, ny, res = grid.nx, grid.ny, grid.res
    nf = grid.nonfree
    mark = bytearray(nf)
    R = r / res
    # per row offset dy: cells dx with (|dx|-0.5)+^2 + (|dy|-0.5)+^2 < R^2
    spans = []
    dymax = int(math.floor(R + 0.5))
    for dy in range(-dymax, dymax + 1):
        ey = max(0.0, abs(dy) - 0.5)
        if ey >= R:
            continue
        lim = 0.5 + math.sqrt(R * R - ey * ey)
        hw = math.ceil(lim) - 1
        spans.append((dy, hw))
    ones = b"\x01" * (nx + 2 * (dymax + 2))
    # boundary cells: non-free with a free 4-neighbour (the nearest non-free
    # cell of any free cell is one of them)
    for cy in range(ny):
        base = cy * nx
        row = nf[base:base + nx]
        up = nf[base + nx:base + 2 * nx] if cy + 1 < ny else None
        dn = nf[base - nx:base] if cy > 0 else None
        if 0 not in row and (up is None or 0 not in up) and (dn is None or 0 not in dn):
            continue  # no free cell here or next to this row
        for cx in range(nx):
            if not row[cx]:
                continue
            if not ((cx > 0 and not row[cx - 1]) or (cx + 1 < nx and not row[cx + 1])
                    or (up is not None and not up[cx]) or (dn is not None and not dn[cx])):
                continue
            for dy, hw in spans:
                y = cy + dy
                if 0 <= y < ny:
                    a, b = max(0, cx - hw), min(nx, cx + hw + 1)
                    mark[y * nx + a:y * nx + b] = ones[:b - a]
    # the outside of the map: distance of cell cx's centre to it is (cx + 0.5) res
    k = 0
    while k < max(nx, ny) and (k + 0.5) < R:
        k += 1
    if k:
        for cy in range(ny):
            b = cy * nx
            mark[b:b + min(k, nx)] = ones[:min(k, nx)]
            mark[b + nx - min(k, nx):b + nx] = ones[:min(k, nx)]
        for cy in list(range(min(k, ny))) + list(range(max(0, ny - k), ny)):
            mark[cy * nx:(cy + 1) * nx] = ones[:nx]
    return mark


def components(grid, blocked):
    """Labels (array of int, -1 blocked) of 4-connected components."""
    nx, n = grid.nx, grid.nx * grid.ny
    label = [-1] * n
    sizes = []
    for s in range(n):
        if blocked[s] or label[s] >= 0:
            continue
        lab = len(sizes)
        label[s] = lab
        stack, count = [s], 0
        while stack:
            i = stack.pop()
            count += 1
            cx = i % nx
            for j in ((i - 1) if cx > 0 else -1, (i + 1) if cx + 1 < nx else -1, i - nx, i + nx):
                if 0 <= j < n and not blocked[j] and label[j] < 0:
                    label[j] = lab
                    stack.append(j)
        sizes.append(count)
    return label, sizes


def segment_blocked(grid, a, b):
    """The straight segment a-b crosses a non-free cell (sampled at res/4)."""
    d = math.hypot(b[0] - a[0], b[1] - a[1])
    steps = max(1, int(math.ceil(d / (grid.res / 4))))
    for k in range(steps + 1):
        t = k / steps
        i = grid.cell(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
        if i is None or grid.nonfree[i]:
            return True
    return False


def way_length(grid, blocked, s, g):
    """Length [m] of the shortest 8-connected way from cell s to cell g over
    the cells not blocked (a diagonal step only where both cells beside it
    are open: no corner cutting); A* with the octile distance. None when g
    is not reachable."""
    nx, n, res = grid.nx, grid.nx * grid.ny, grid.res
    gx, gy = g % nx, g // nx
    r2 = math.sqrt(2.0)

    def h(i):
        dx, dy = abs(i % nx - gx), abs(i // nx - gy)
        return (max(dx, dy) + (r2 - 1.0) * min(dx, dy))

    dist = {s: 0.0}
    heap = [(h(s), 0.0, s)]
    while heap:
        _, d, i = heapq.heappop(heap)
        if i == g:
            return d * res
        if d > dist.get(i, math.inf):
            continue
        cx = i % nx
        for ddx, ddy in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)):
            x, j = cx + ddx, i + ddx + ddy * nx
            if x < 0 or x >= nx or j < 0 or j >= n or blocked[j]:
                continue
            if ddx and ddy and (blocked[i + ddx] or blocked[i + ddy * nx]):
                continue
            nd = d + (r2 if ddx and ddy else 1.0)
            if nd < dist.get(j, math.inf):
                dist[j] = nd
                heapq.heappush(heap, (nd + h(j), nd, j))
    return None


def analyse(grid, radius):
    t0 = time.time()
    ends_block = too_close(grid, CLEAR_ENDS)
    disc_block = too_close(grid, radius + DISC_MARGIN)
    label, sizes = components(grid, disc_block)
    by_comp = collections.defaultdict(list)
    for i in range(grid.nx * grid.ny):
        if not ends_block[i] and label[i] >= 0:
            by_comp[label[i]].append(i)
    cands = [i for lst in by_comp.values() for i in lst]
    cands.sort()
    free = grid.nx * grid.ny - sum(grid.nonfree)
    return {
        "label": label, "by_comp": by_comp, "cands": cands, "disc_block": disc_block,
        "free_cells": free, "components": len(sizes),
        "largest_component_cells": max(sizes) if sizes else 0,
        "seconds": time.time() - t0,
    }


def draw_pairs(grid, an, rng, n):
    """n pairs (start x y heading_deg, goal x y, behind); raises when the map
    has none that meet the rules."""
    cands, label, by_comp = an["cands"], an["label"], an["by_comp"]
    if not cands:
        raise ValueError("no free cell with 0.5 m clearance where the robot fits")
    pairs = []
    for k in range(n):
        behind_needed = k % BEHIND_EVERY == 0
        for attempt in range(20000):
            s = cands[rng.randrange(len(cands))]
            comp = by_comp[label[s]]
            g = comp[rng.randrange(len(comp))]
            a, b = grid.centre(s), grid.centre(g)
            dist = math.hypot(b[0] - a[0], b[1] - a[1])
            if dist < MIN_DIST:
                continue
            behind = segment_blocked(grid, a, b)
            if behind_needed and not behind:
                continue
            heading = rng.uniform(-180.0, 180.0)
            way = way_length(grid, an["disc_block"], s, g)
            pairs.append({"pair": k, "start": [round(a[0], 4), round(a[1], 4), round(heading, 1)],
                          "goal": [round(b[0], 4), round(b[1], 4)],
                          "distance_m": round(dist, 3), "way_m": round(way or dist, 3),
                          "behind": behind,
                          "component": label[s]})
            break
        else:
            raise ValueError(f"pair {k}: no start/goal pair found "
                             f"({'behind obstacles, ' if behind_needed else ''}>= {MIN_DIST} m "
                             "apart, one component) in 20000 draws")
    return pairs


# ----------------------------------------------------------------------------
# Runs


def base_config(mode, out):
    """The base config of a mode, written into `out` where it must lose the
    office's boxes (m1, explore)."""
    if mode == "risk-eval":
        # the app's defaults and the navigate runs' robot
        nav = read_ini(os.path.join(ROOT, BASE["navigate"]))
        path = os.path.join(out, "base_risk-eval.ini")
        os.makedirs(out, exist_ok=True)
        with open(path, "w") as f:
            f.write("; written by scripts/validate_maps.py: risknav-risk-eval's defaults, the\n"
                    "; robot of " + BASE["navigate"] + "\n[RiskEval]\n[Robot]\nradius = "
                    + str(ini_get(nav, "Robot", "radius", 0.25)) + "\n")
        return path
    src = os.path.join(ROOT, BASE[mode])
    if mode == "navigate":
        return src
    with open(src) as f:
        text = strip_sections(f.read(), ("Clutter", "DoorPedestrian", "CorridorWalker"))
    # the engine's and the limiters' relative paths stay valid next to the source
    path = os.path.join(out, f"base_{mode}.ini")
    text = ("; " + BASE[mode] + " without its boxes, written by scripts/validate_maps.py\n"
            + text)
    os.makedirs(out, exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


def run_pair(job):
    m, seed, p, a = job["map"], job["seed"], job["pair"], job["args"]
    out = job["out"]
    mode = a.mode
    v = job["max_v"]
    # the budget grows with the way the robot must drive, not the straight
    # line: a goal behind a wall may be ten times as far
    limit = round(60 + 4 * max(p["distance_m"], p.get("way_m", 0.0)) / v, 1)
    sx, sy, sh = p["start"]
    gx, gy = p["goal"]
    sets = [f"World.map_file={job['map_path']}"]
    if mode == "risk-eval":
        app = APPS["risk-eval"]
        sets = [f"RiskEval.map_file={job['map_path']}", f"RiskEval.start={sx} {sy}",
                f"RiskEval.goal={gx} {gy}"]
    elif mode == "explore":
        app = APPS["explore"]
        sets += [f"Explore.start={sx} {sy} {sh}", f"Explore.destinations={gx} {gy}",
                 "Explore.modes=adaptive", f"Explore.duration_max={limit}"]
    else:
        app = APPS["navigate"]
        sets += [f"Navigate.start={sx} {sy} {sh}", f"Navigate.goals={gx} {gy}",
                 f"Navigate.duration_max={limit}"]
        if a.planner:
            sets.append(f"Navigate.global_planner={a.planner}")
        if a.localization:
            sets.append(f"Navigate.localization={a.localization}")
    sets += a.set or []
    cmd = [app, "-q", "-o", out, "--seed", str(seed)]
    for s in sets:
        cmd += ["--set", s]
    cmd.append(job["config"])
    rec = {"map": m, "seed": seed, "pair": p["pair"], "start": p["start"], "goal": p["goal"],
           "distance_m": p["distance_m"], "way_m": p.get("way_m"), "behind": p["behind"],
           "time_limit_s": limit,
           "out": out, "command": cmd}
    t0 = time.time()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=a.run_timeout)
        rc, err = r.returncode, r.stderr.strip()
    except subprocess.TimeoutExpired:
        rc = None
        err = f"no exit after {a.run_timeout} s wall time (killed)"
    rec["wall_s"] = round(time.time() - t0, 1)
    rec["exit_code"] = rc
    rec["stderr"] = err[-2000:] if err else ""
    rec.update(judge(mode, out, job["tol"], p, rc, err))
    if rec["time_s"] is not None:
        rec["time_s"] = round(rec["time_s"], 2)
    if mode == "risk-eval":
        rec["time_s"] = rec["wall_s"]
    return rec


def judge(mode, out, tol, p, rc, err):
    j = {"reached": False, "collisions": 0, "status": None, "time_s": None,
         "final_distance_m": None, "belief_error_m": None, "driven_m": None,
         "navigation_error": ""}
    summ = os.path.join(out, "summary.json")
    if rc != 0 or not os.path.exists(summ):
        if rc is None:
            j["reason"] = "hung: " + err
        elif rc < 0:
            j["reason"] = f"crashed (signal {-rc})"
        else:
            j["reason"] = f"exit {rc}: " + (err.splitlines()[-1] if err else "(no message)")
        return j
    with open(summ) as f:
        s = json.load(f)
    gx, gy = p["goal"]
    if mode == "risk-eval":
        j["status"] = s.get("status")
        best = s.get("best") or {}
        routes = s.get("routes") or []
        src = {r["name"]: r["source"] for r in routes}
        j["best_route"] = best.get("route")
        j["best_source"] = src.get(best.get("route"))
        j["best_U"] = best.get("U")
        j["routes"] = collections.Counter(r["source"] for r in routes)
        j["excluded_plain"] = sum(1 for r in s.get("table") or []
                                  if r["sensing"] == "none" and r["excluded"])
        j["reached"] = j["status"] == "ok" and j["best_U"] is not None
        if not j["reached"]:
            nw = s.get("no_way") or {}
            j["reason"] = (j["status"] or "?") + (": " + nw["reason"] if nw.get("reason") else "")
        return j
    if mode == "explore":
        md = (s.get("modes") or [{}])[0]
        j["status"] = s.get("status")
        j["time_s"] = md.get("time_s")
        j["collisions"] = md.get("collisions", 0)
        j["driven_m"] = md.get("distance_m")
        dest = (md.get("destinations") or ["?"])[0]
        j["navigation_error"] = f"destination {dest}"
        last = None
        with open(os.path.join(out, "cycles.csv")) as f:
            hdr = f.readline().strip().split(",")
            for line in f:
                last = line
        if last:
            row = dict(zip(hdr, last.strip().split(",")))
            tx, ty = float(row["x"]), float(row["y"])
            j["final_distance_m"] = math.hypot(tx - gx, ty - gy)
            j["belief_error_m"] = math.hypot(float(row["ego_x"]) - tx, float(row["ego_y"]) - ty)
        # the app's own figures at the arrival (the last row is a cycle before it)
        de = md.get("destination_error_m") or [None]
        if de[0] is not None:
            j["final_distance_m"] = de[0]
        be = md.get("destination_belief_error_m") or [None]
        if be[0] is not None:
            j["belief_error_m"] = be[0]
        status_ok = dest == "reached"
    else:
        j["status"] = s.get("status")
        j["time_s"] = s.get("time_s")
        j["collisions"] = s.get("collisions", 0)
        j["navigation_error"] = s.get("navigation_error") or ""
        ex, ey = s["end_pose"][0], s["end_pose"][1]
        j["final_distance_m"] = math.hypot(ex - gx, ey - gy)
        # the app's own true-pose figure: the least true distance to the goal
        # while it was the target (a waypoint is reached when the robot
        # passes within the tolerance; it then stops a little beyond)
        if s.get("goal_true_distance_m") is not None:
            j["final_distance_m"] = s["goal_true_distance_m"]
        j["belief_error_m"] = s.get("pose_error_final_m")
        j["driven_m"] = s.get("distance_m")
        status_ok = j["status"] == "goal_reached"
    for k in ("final_distance_m", "belief_error_m", "driven_m"):
        if j[k] is not None:
            j[k] = round(j[k], 3)
    # + 3 cm: the true track is sampled every physics step (5.5 cm at 1.1 m/s),
    # so its nearest sample may miss the closest approach by half of that
    j["reached"] = j["final_distance_m"] is not None and j["final_distance_m"] <= tol + 0.03
    why = []
    if not j["reached"]:
        r = j["status"] or "?"
        ne = j["navigation_error"]
        if ne:
            r = ne if ne.startswith(r) else r + ": " + ne
        if status_ok:
            r += f" (by its belief; truly {j['final_distance_m']:.2f} m off)"
        why.append(r)
    elif not status_ok:
        why.append(f"reached, but status {j['status']}"
                   + (": " + j["navigation_error"] if j["navigation_error"] else ""))
    if j["collisions"]:
        why.append(f"{j['collisions']} collision(s)")
    if why:
        j["reason"] = "; ".join(why)
    return j


def reason_keys(reason):
    """The parts of a failure's reason, each with its numbers hidden (not an
    exit code's), to group alike ones: "stalled", "collision(s)", ..."""
    keys = []
    for part in re.split(r"; (?=\d+ collision\(s\)$)", reason):
        if part.startswith("stalled:"):
            keys.append("stalled (stall_timeout)")
            continue
        if part.endswith(" collision(s)"):
            keys.append("collision(s)")
            continue
        m = re.match(r"exit -?\d+: ", part)
        head = m.group(0) if m else ""
        keys.append(head + re.sub(r"-?\d+(\.\d+)?(e-?\d+)?", "#", part[len(head):]))
    return keys


# ----------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=None, help="one seed (default 1)")
    ap.add_argument("--seeds", default=None, help="comma-separated seeds, e.g. 1,2,3")
    ap.add_argument("--maps", default=None,
                    help="comma-separated map names (default all; none: only --map-file's)")
    ap.add_argument("--map-file", action="append", default=[],
                    help="one more map (any format the apps read; a plain image at [World] "
                         "map_resolution / map_origin_*, e.g. via --set), named after its "
                         "file; repeatable")
    ap.add_argument("--mode", choices=("navigate", "m1", "explore", "risk-eval"),
                    default="navigate")
    ap.add_argument("--planner", choices=("grid", "risk", "none"), default=None,
                    help="passed as --set Navigate.global_planner=...; absent: nothing passed")
    ap.add_argument("--localization", choices=("ground_truth", "mcl"), default=None,
                    help="navigate/m1: Navigate.localization (MCL: [Localization] as the "
                         "config has it, its particles around the start)")
    ap.add_argument("--pairs", type=int, default=12, help="pairs per map and seed (default 12)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at a time (default 2)")
    ap.add_argument("--out", default="/tmp/validate_maps",
                    help="output folder: DIR/results.json, DIR/MODE/MAP/seedS_pairNN/ "
                         "(default /tmp/validate_maps)")
    ap.add_argument("--set", action="append", metavar="SECTION.KEY=V",
                    help="passed to every run (repeatable)")
    ap.add_argument("--run-timeout", type=float, default=3600,
                    help="[s] wall time after which a run is killed (default 3600)")
    ap.add_argument("--list", action="store_true", help="list the maps and exit")
    ap.add_argument("--dry-run", action="store_true", help="draw the pairs, run nothing")
    a = ap.parse_args()
    if a.mode in ("explore", "risk-eval") and (a.planner or a.localization):
        ap.error("--planner and --localization are for --mode navigate / m1")
    if a.seeds and a.seed is not None:
        ap.error("give --seed or --seeds, not both")
    try:
        seeds = [int(s) for s in a.seeds.split(",")] if a.seeds else [a.seed if a.seed is not None else 1]
    except ValueError:
        ap.error(f"--seeds {a.seeds!r}: comma-separated integers")
    if a.list:
        for k, (p, what) in MAPS.items():
            print(f"{k:18s} {p}  ({what})")
        return 0
    maps = collections.OrderedDict()
    names = [] if a.maps == "none" else (a.maps.split(",") if a.maps else list(MAPS))
    for n in names:
        if n not in MAPS:
            ap.error(f"--maps: unknown map {n!r} (known: {', '.join(MAPS)})")
        p = MAPS[n][0]
        maps[n] = p if os.path.isabs(p) else os.path.join(ROOT, p)
    for p in a.map_file:
        n = re.sub(r"\.(gz)$", "", os.path.basename(p))
        n = re.sub(r"\.(yaml|yml|png|pgm|gridmap|simplemap|bmp)$", "", n)
        if n in maps:
            n = f"{n}_{len(maps)}"
        maps[n] = os.path.abspath(p)
    if not maps:
        ap.error("no maps")
    for app in [APPS[a.mode if a.mode in ("explore", "risk-eval") else "navigate"]]:
        if not a.dry_run and not os.access(app, os.X_OK):
            sys.exit(f"validate_maps: {app} is missing (bash scripts/build.sh)")

    os.makedirs(a.out, exist_ok=True)
    config = base_config(a.mode, os.path.join(a.out, "configs"))
    cfg = read_ini(config)
    for s in a.set or []:  # the runs' overrides count for the pairs too
        m = re.match(r"([^.=]+)\.([^=]+)=(.*)$", s)
        if not m:
            ap.error(f"--set {s!r}: SECTION.KEY=VALUE")
        if not cfg.has_section(m.group(1)):
            cfg.add_section(m.group(1))
        cfg[m.group(1)][m.group(2)] = m.group(3)
    radius = float(ini_get(cfg, "Robot", "radius", 0.25))
    max_v = float(ini_get(cfg, "Robot", "max_v", 0.8))
    tol = float(ini_get(cfg, "Explore" if a.mode == "explore" else "Navigate",
                        "goal_tolerance", 0.3))
    if a.mode == "risk-eval":
        max_v = 1.0  # no motion: the time budget is not used

    results = {"mode": a.mode, "planner": a.planner, "localization": a.localization,
               "seeds": seeds, "config": config, "sets": a.set or [],
               "robot_radius_m": radius, "max_v_mps": max_v, "goal_tolerance_m": tol,
               "rules": {"clearance_ends_m": CLEAR_ENDS, "disc_clearance_m": radius + DISC_MARGIN,
                         "min_distance_m": MIN_DIST, "behind_every": BEHIND_EVERY},
               "maps": {}, "runs": []}
    jobs = []
    for n, path in maps.items():
        entry = {"file": path}
        results["maps"][n] = entry
        t0 = time.time()
        try:
            grid = load_grid(path, cfg, os.path.join(a.out, "grids", n))
            an = analyse(grid, radius)
        except (OSError, ValueError, KeyError, struct.error) as e:
            entry["error"] = f"map not usable: {e}"
            log(f"[{n}] {entry['error']}")
            continue
        entry.update({"size_cells": [grid.nx, grid.ny], "resolution_m": round(grid.res, 6),
                      "bounds": [round(grid.x0, 3), round(grid.x0 + grid.nx * grid.res, 3),
                                 round(grid.y0, 3), round(grid.y0 + grid.ny * grid.res, 3)],
                      "free_cells": an["free_cells"], "disc_components": an["components"],
                      "largest_component_cells": an["largest_component_cells"],
                      "start_goal_cells": len(an["cands"]), "pairs": {}})
        log(f"[{n}] {grid.nx} x {grid.ny} cells at {grid.res:g} m, {an['free_cells']} free, "
            f"{len(an['cands'])} may hold a start/goal ({time.time() - t0:.1f} s)")
        for seed in seeds:
            rng = random.Random(f"validate_maps:{seed}:{n}")
            try:
                pairs = draw_pairs(grid, an, rng, a.pairs)
            except ValueError as e:
                entry["pairs"][str(seed)] = {"error": str(e)}
                log(f"[{n}] seed {seed}: {e}")
                continue
            entry["pairs"][str(seed)] = pairs
            for p in pairs:
                jobs.append({"map": n, "map_path": path, "seed": seed, "pair": p, "args": a,
                             "config": config, "max_v": max_v, "tol": tol,
                             "out": os.path.join(a.out, a.mode, n, f"seed{seed}_pair{p['pair']:02d}")})
    if a.dry_run:
        print(json.dumps(results["maps"], indent=1))
        return 0

    log(f"{len(jobs)} runs, {a.jobs} at a time, into {a.out}")
    t0 = time.time()
    done = 0
    with concurrent.futures.ThreadPoolExecutor(max(1, a.jobs)) as ex:
        futs = {ex.submit(run_pair, j): j for j in jobs}
        for f in concurrent.futures.as_completed(futs):
            rec = f.result()
            results["runs"].append(rec)
            done += 1
            el = time.time() - t0
            eta = el / done * (len(jobs) - done)
            log(f"[{done}/{len(jobs)}] {rec['map']} seed {rec['seed']} pair {rec['pair']}: "
                f"{'reached' if rec['reached'] else 'NOT reached'}"
                f"{'' if not rec.get('reason') else ' - ' + rec['reason']} "
                f"({rec['wall_s']} s; ETA {eta / 60:.1f} min)")
    results["runs"].sort(key=lambda r: (list(maps).index(r["map"]), r["seed"], r["pair"]))
    results["wall_time_s"] = round(time.time() - t0, 1)
    report(results, maps)
    with open(os.path.join(a.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    log(f"results: {os.path.join(a.out, 'results.json')}")
    return 0


def report(results, maps):
    rows = []
    tot = collections.Counter()
    tot_reasons = collections.Counter()
    all_errs = []

    def belief(errs):
        if not errs:
            return "-"
        s = sorted(errs)
        return f"{s[len(s) // 2]:.3f} ({s[-1]:.3f})"

    for n in maps:
        e = results["maps"][n]
        runs = [r for r in results["runs"] if r["map"] == n]
        if "error" in e:
            rows.append(f"| {n} | 0 | - | - | - | {e['error']} |")
            continue
        bad = [f"seed {s}: {v['error']}" for s, v in e["pairs"].items() if isinstance(v, dict)]
        reached = sum(r["reached"] for r in runs)
        col_runs = sum(1 for r in runs if r["collisions"])
        col_eps = sum(r["collisions"] or 0 for r in runs)
        reasons = collections.Counter(k for r in runs if r.get("reason")
                                      for k in reason_keys(r["reason"]))
        errs = [r["belief_error_m"] for r in runs if r["belief_error_m"] is not None]
        all_errs.extend(errs)
        tot.update({"pairs": len(runs), "reached": reached, "col_runs": col_runs,
                    "col_eps": col_eps})
        tot_reasons.update(reasons)
        fails = "; ".join(f"{k} x{v}" for k, v in reasons.most_common()) or "none"
        if bad:
            fails += "; no pairs: " + "; ".join(bad)
        rows.append(f"| {n} | {len(runs)} | {reached}/{len(runs)} | {col_runs} ({col_eps}) | "
                    f"{belief(errs)} | {fails} |")
    title = (f"mode {results['mode']}, planner {results['planner'] or '(not passed)'}, "
             f"localization {results['localization'] or '(config)'}, seeds "
             f"{','.join(map(str, results['seeds']))}")
    print(f"### validate_maps: {title}\n")
    print("| map | pairs | " + ("route found" if results["mode"] == "risk-eval" else
                               "reached (true pose)") + " | runs with collisions (episodes) | "
          "belief error at the end [m], median (max) | "
          "failures by reason (a run may count under two) |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(r)
    fails = "; ".join(f"{k} x{v}" for k, v in tot_reasons.most_common()) or "none"
    print(f"| **overall** | {tot['pairs']} | **{tot['reached']}/{tot['pairs']}** | "
          f"{tot['col_runs']} ({tot['col_eps']}) | {belief(all_errs)} | {fails} |")
    if results["mode"] == "risk-eval":
        won = collections.Counter(r.get("best_source") for r in results["runs"] if r["reached"])
        cands = collections.Counter()
        for r in results["runs"]:
            cands.update(r.get("routes") or {})
        excl = sum(r.get("excluded_plain") or 0 for r in results["runs"])
        print(f"\nThe best row's route came from: "
              + ", ".join(f"{k} {v}" for k, v in won.most_common())
              + f"; candidates over all runs: "
              + ", ".join(f"{k} {v}" for k, v in cands.most_common())
              + f", of which {excl} excluded (collide or a sensing detour fails).")
    failed = [r for r in results["runs"] if r.get("reason")]
    if failed:
        print("\nEvery failure (start x y heading_deg -> goal x y; straight distance; "
              "way = the shortest way for the disc on the true map; behind = the segment "
              "crosses a non-free cell):\n")
        for r in failed:
            s, g = r["start"], r["goal"]
            print(f"- {r['map']} seed {r['seed']} pair {r['pair']}: ({s[0]}, {s[1]}, {s[2]}) -> "
                  f"({g[0]}, {g[1]}), {r['distance_m']} m, way {r.get('way_m')} m"
                  f"{', behind' if r['behind'] else ''}: "
                  f"{'' if r['reason'].startswith('exit') else 'exit ' + str(r['exit_code']) + ', '}"
                  f"{r['reason']}; final distance "
                  f"{r['final_distance_m']} m, belief error {r['belief_error_m']} m, "
                  f"driven {r['driven_m']} m in {r['time_s']} s -> {r['out']}")


if __name__ == "__main__":
    sys.exit(main())
