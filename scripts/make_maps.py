#!/usr/bin/env python3
"""Draws the bundled dataset maps as 8-bit grey PNGs (white = free, black =
occupied), 0.05 m per pixel, origin = lower-left corner at (0, 0).

Rectangles are given in metres as (x0, y0, x1, y1). No third-party modules:
PNG is written with zlib. Run from anywhere: python3 scripts/make_maps.py
"""
import os
import struct
import zlib

RES = 0.05
HERE = os.path.dirname(os.path.abspath(__file__))
DATASETS = os.path.join(HERE, "..", "datasets")


class Bitmap:
    def __init__(self, w_m, h_m, fill=0):
        self.w, self.h = round(w_m / RES), round(h_m / RES)
        self.px = [bytearray([fill]) * self.w for _ in range(self.h)]

    def rect(self, x0, y0, x1, y1, v):
        """Paints cells whose centres lie in [x0, x1) x [y0, y1) (metres)."""
        cx0, cx1 = round(x0 / RES), round(x1 / RES)
        cy0, cy1 = round(y0 / RES), round(y1 / RES)
        for cy in range(max(0, cy0), min(self.h, cy1)):
            row = self.px[self.h - 1 - cy]  # image row 0 is the top (max y)
            for cx in range(max(0, cx0), min(self.w, cx1)):
                row[cx] = v

    def free(self, *r):
        self.rect(*r, 255)

    def wall(self, *r):
        self.rect(*r, 0)

    def save(self, path):
        raw = b"".join(b"\x00" + bytes(r) for r in self.px)
        def chunk(tag, data):
            c = struct.pack(">I", len(data)) + tag + data
            return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
        png = b"\x89PNG\r\n\x1a\n"
        png += chunk(b"IHDR", struct.pack(">IIBBBBB", self.w, self.h, 8, 0, 0, 0, 0))
        png += chunk(b"IDAT", zlib.compress(raw, 9))
        png += chunk(b"IEND", b"")
        with open(path, "wb") as f:
            f.write(png)
        print(f"{path}: {self.w} x {self.h} px ({self.w * RES:g} x {self.h * RES:g} m)")


def corridor_doors():
    """30 x 10 m: a 3 m corridor (y 3..6) with three doors on its upper side at
    the positions of Choi et al. (002) section 3.3: 11.21-12.02, 13.68-15.10,
    17.53-18.95 m. Alcoves and pillars on the lower side give the localizer
    features along the corridor axis."""
    b = Bitmap(30, 10)
    b.free(0.5, 3.0, 29.5, 6.0)                  # corridor
    b.free(10.0, 6.15, 13.0, 9.5)                # room behind door 1
    b.free(13.15, 6.15, 16.5, 9.5)               # room behind door 2
    b.free(16.65, 6.15, 20.5, 9.5)               # room behind door 3
    for x0, x1 in ((11.21, 12.02), (13.68, 15.10), (17.53, 18.95)):
        b.free(x0, 5.95, x1, 6.2)                # doorways through the 0.15 m wall
    for x0, y0, x1 in ((2.5, 2.4, 3.7), (8.0, 2.6, 8.6), (15.0, 2.0, 17.0),
                       (23.0, 2.6, 23.5), (26.0, 2.2, 27.8)):
        b.free(x0, y0, x1, 3.0)                  # alcoves on the lower wall
    for x0 in (5.5, 11.0, 19.5):
        b.wall(x0, 3.0, x0 + 0.3, 3.2)           # pillars
    b.wall(4.0, 5.8, 5.2, 6.0)                   # a cabinet against the upper wall
    b.wall(24.0, 5.7, 24.6, 6.0)
    return b


def office():
    """20 x 14 m: lower rooms, a 2 m corridor, upper rooms with furniture and a
    0.8 m passage between two desks (the narrow space of Miura et al., M1)."""
    b = Bitmap(20, 14)
    b.free(0.3, 0.3, 19.7, 13.7)
    b.wall(0.3, 5.85, 19.7, 6.0)                 # corridor walls
    b.wall(0.3, 8.0, 19.7, 8.15)
    b.wall(6.5, 0.3, 6.65, 5.85)                 # lower room walls
    b.wall(13.0, 0.3, 13.15, 5.85)
    b.wall(9.9, 8.15, 10.05, 13.7)               # upper room wall
    for x0 in (2.5, 9.0, 16.0):
        b.free(x0, 5.8, x0 + 1.0, 6.05)          # doors of the lower rooms
    for x0 in (4.0, 15.0):
        b.free(x0, 7.95, x0 + 1.0, 8.2)          # doors of the upper rooms
    # Furniture in the upper-left room: two desks with a 0.8 m gap between them.
    b.wall(1.0, 10.0, 4.1, 10.8)
    b.wall(4.9, 10.0, 8.5, 10.8)
    b.wall(1.0, 12.6, 3.0, 13.7)                 # shelves
    b.wall(7.0, 12.8, 9.9, 13.7)
    # Lower rooms: tables and cabinets.
    b.wall(1.0, 1.0, 3.0, 2.2)
    b.wall(8.0, 2.0, 11.5, 3.0)
    b.wall(14.5, 0.3, 19.7, 1.0)
    b.wall(17.5, 3.0, 18.5, 4.5)
    # Upper-right room: a meeting table.
    b.wall(13.0, 10.0, 17.0, 11.5)
    return b


def risk_two_routes():
    """24 x 14 m, for the path evaluation of Irie et al. (M2): from a start room
    to a goal room either through a 1.2 m wide corridor (route B, short and
    narrow) or through a 3 m wide hall (route A, longer and wider). A pillar
    stands against the hall's upper wall (sensing point SP1 is next to it)."""
    b = Bitmap(24, 14)
    b.free(0.5, 4.0, 4.0, 13.0)                  # start room
    b.free(20.0, 4.0, 23.5, 13.0)                # goal room
    b.free(4.0, 6.4, 20.0, 7.6)                  # route B: the narrow corridor (1.2 m)
    b.free(4.0, 9.5, 20.0, 12.5)                 # route A: the wide hall
    b.wall(9.2, 11.9, 9.8, 12.5)                 # the pillar by SP1
    return b


def narrow_doors():
    """24 x 6 m: a 1.2 m corridor (y 2.4..3.6) whose walls lie inside the
    afraid detector's collision circle, with two crossings: rooms above and
    below the corridor at x 5.5-9.5 (doors x 7.0-7.9) and at x 13.5-17.5
    (doors x 15.0-15.9), people crossing from one room to the other. For the
    multi-world validation of the afraid learner."""
    b = Bitmap(24, 6)
    b.free(0.5, 2.4, 23.5, 3.6)                  # corridor
    for x0 in (5.5, 13.5):
        b.free(x0, 3.75, x0 + 4.0, 5.5)          # upper room
        b.free(x0, 0.5, x0 + 4.0, 2.25)          # lower room
    for x0 in (7.0, 15.0):
        b.free(x0, 3.5, x0 + 0.9, 3.8)           # upper door
        b.free(x0, 2.2, x0 + 0.9, 2.5)           # lower door
    for x0 in (3.0, 11.0, 19.5):
        b.free(x0, 3.6, x0 + 0.4, 3.75)          # shallow niches (features along the axis)
    return b


def t_junction():
    """24 x 16 m: a 2.5 m main corridor (y 6..8.5) ending blind at x = 1, a
    branch up at x 10.75..13.25 ending blind at y = 15, a door on the main
    corridor's lower wall (x 5.5-6.5) and one on the branch's right wall
    (y 11.0-12.0), with rooms behind them."""
    b = Bitmap(24, 16)
    b.free(1.0, 6.0, 23.0, 8.5)                  # main corridor
    b.free(10.75, 8.5, 13.25, 15.0)              # branch, dead end at the top
    b.free(3.5, 1.0, 9.0, 5.85)                  # room below the main corridor
    b.free(5.5, 5.8, 6.5, 6.05)                  # its door
    b.free(13.4, 9.5, 18.0, 14.0)                # room right of the branch
    b.free(13.2, 11.0, 13.45, 12.0)              # its door
    b.wall(17.0, 6.0, 17.4, 6.3)                 # a pillar (feature)
    b.wall(3.0, 8.2, 3.6, 8.5)                   # a cabinet (feature)
    return b


def furnished_room(stale):
    """14 x 10 m: a room with mapped furniture around which the robot loops,
    two doors on its upper wall to a second room. stale=True draws the map the
    robot was given, which still holds a cabinet (x 9.0-10.0, y 0.5-0.95) that
    is gone from the world; the world also holds an unmapped box (a [Clutter]
    disc in the world file)."""
    b = Bitmap(14, 10)
    b.free(0.5, 0.5, 13.5, 6.5)                  # main room
    b.free(0.5, 6.65, 13.5, 9.5)                 # upper room
    b.free(3.0, 6.45, 4.0, 6.7)                  # door 1
    b.free(9.5, 6.45, 10.5, 6.7)                 # door 2
    b.wall(5.0, 2.6, 9.0, 4.2)                   # central table
    b.wall(0.5, 0.5, 1.5, 2.0)                   # shelves
    b.wall(12.5, 3.0, 13.5, 5.0)                 # cabinet on the right wall
    b.wall(5.5, 8.3, 8.5, 9.5)                   # upper room desk
    if stale:
        b.wall(9.0, 0.5, 10.0, 0.95)             # removed since the map was made
    return b


if __name__ == "__main__":
    corridor_doors().save(os.path.join(DATASETS, "corridor-doors", "corridor.png"))
    office().save(os.path.join(DATASETS, "office", "office.png"))
    risk_two_routes().save(os.path.join(DATASETS, "risk-two-routes", "two_routes.png"))
    worlds = os.path.join(DATASETS, "validation")
    os.makedirs(worlds, exist_ok=True)
    narrow_doors().save(os.path.join(worlds, "narrow_doors.png"))
    t_junction().save(os.path.join(worlds, "t_junction.png"))
    furnished_room(False).save(os.path.join(worlds, "furnished_room.png"))
    furnished_room(True).save(os.path.join(worlds, "furnished_room_stale.png"))
