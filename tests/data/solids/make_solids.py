#!/usr/bin/env python3
"""Writes solids.city.json: buildings that are not height fields, for the 3D shrinking route
(--solid-step). Each is a profile in the x-z plane (counter-clockwise seen from -y) extruded
along y, with semantic surfaces; every face is wound counter-clockwise seen from outside."""
import json

vertices, objects = [], {}


def vid(p):
    p = tuple(round(c * 1000) for c in p)  # millimetres (transform scale 0.001)
    if p not in index:
        index[p] = len(vertices)
        vertices.append(list(p))
    return index[p]


index = {}


def extrude(name, profile, x0, y0, depth):
    faces, kinds = [], []
    n = len(profile)
    front = [(x0 + x, y0, z) for x, z in profile]
    back = [(x0 + x, y0 + depth, z) for x, z in reversed(profile)]
    faces += [[[vid(p) for p in front]], [[vid(p) for p in back]]]
    kinds += ["WallSurface", "WallSurface"]
    for k in range(n):
        (ax, az), (bx, bz) = profile[k], profile[(k + 1) % n]
        quad = [(x0 + ax, y0, az), (x0 + ax, y0 + depth, az), (x0 + bx, y0 + depth, bz),
                (x0 + bx, y0, bz)]
        faces.append([[vid(p) for p in quad]])
        if az == bz == 0:
            kinds.append("GroundSurface")
        elif ax == bx:
            kinds.append("WallSurface")
        elif bx < ax:  # walked right to left along the top: faces up
            kinds.append("RoofSurface")
        else:  # walked left to right above the ground: faces down
            kinds.append("OuterCeilingSurface")
    surfaces = sorted(set(kinds))
    objects[name] = {
        "type": "Building",
        "geometry": [{"type": "Solid", "lod": "2", "boundaries": [faces],
                      "semantics": {"surfaces": [{"type": t} for t in surfaces],
                                    "values": [[surfaces.index(t) for t in kinds]]}}]}


# An arcade: a bar 30 m long with a passage 6 m wide and 4 m high through it.
extrude("arcade", [(0, 0), (12, 0), (12, 4), (18, 4), (18, 0), (30, 0), (30, 12), (0, 12)], 0, 0, 10)
# Upper floors overhanging the ground floor by 4 m, under a gabled roof.
extrude("overhang", [(0, 0), (10, 0), (10, 4), (14, 4), (14, 10), (7, 14), (0, 10)], 40, 0, 12)
# A gabled house and a shed behind each building.
extrude("house", [(0, 0), (8, 0), (8, 6), (4, 10), (0, 6)], 0, 30, 12)
extrude("shed_behind_arcade", [(0, 0), (3, 0), (3, 3), (0, 3)], 13.5, -15, 3)
extrude("shed_behind_overhang", [(0, 0), (3, 0), (3, 3), (0, 3)], 45, -15, 3)
extrude("shed_behind_house", [(0, 0), (3, 0), (3, 3), (0, 3)], 2.5, 50, 3)

city = {"type": "CityJSON", "version": "2.0",
        "transform": {"scale": [0.001, 0.001, 0.001], "translate": [85000.0, 446000.0, 0.0]},
        "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/7415"},
        "CityObjects": objects, "vertices": vertices}
with open("solids.city.json", "w") as f:
    json.dump(city, f, separators=(",", ":"))

# The same city as LoD2 models often come: without GroundSurface faces.
for o in objects.values():
    g = o["geometry"][0]
    sem = g["semantics"]
    kept = [i for i, v in enumerate(sem["values"][0]) if sem["surfaces"][v]["type"] != "GroundSurface"]
    g["boundaries"][0] = [g["boundaries"][0][i] for i in kept]
    sem["values"][0] = [sem["values"][0][i] for i in kept]
with open("solids_no_ground.city.json", "w") as f:
    json.dump(city, f, separators=(",", ":"))
