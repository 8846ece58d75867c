#!/usr/bin/python3
"""Match produced junction polygons with the intersections of an osm2streets case.

usage: junction-match.py JUNCTIONS.geojson CASE_DIR [--kinds K,K,..] [--all-roads] [--min-iou X]

Reference: CASE_DIR/geometry.json, features with properties.type == "intersection"
(osm2streets marks each polygon "road" or "intersection"; intersections carry
intersection_kind: Intersection, Connection, Fork, Terminus, MapEdge).
By default only reference intersections of kinds Intersection,Connection,Fork,Terminus
(not MapEdge) that end at least one car road are kept; car road = a geometry.json road
whose first OSM way has highway=motorway..residential/service/living_street/unclassified/
*_link in CASE_DIR/input.osm (or input.osm.pbf, read through osmium). --all-roads keeps
intersections of footways/cycleways too. Produced features whose "kind" or
"intersection_kind" property is MapEdge are dropped as well.
Matching: in UTM (zone of the data), every produced/reference pair that overlaps is a
candidate; pairs are taken greedily by decreasing IoU, one-to-one.
Prints one line:
  case=<c> produced=<n> reference=<n> matched=<n> unmatched_produced=<n> unmatched_reference=<n>
  mean_iou=<x> matched_iou50=<n> reference_overlapped=<n>
(reference_overlapped: reference polygons overlapping any produced one, one-to-many allowed).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

from pyproj import Transformer
from shapely.geometry import shape
from shapely.ops import transform
import warnings
warnings.filterwarnings("ignore", message="STRtree will be changed")
from shapely.strtree import STRtree

CAR = {"motorway", "trunk", "primary", "secondary", "tertiary", "unclassified", "residential",
       "living_street", "service", "motorway_link", "trunk_link", "primary_link",
       "secondary_link", "tertiary_link", "road"}


def way_highways(case):
    path = os.path.join(case, "input.osm")
    tmp = None
    if not os.path.exists(path):
        pbf = os.path.join(case, "input.osm.pbf")
        tmp = tempfile.NamedTemporaryFile(suffix=".osm", delete=False)
        tmp.close()
        subprocess.run(["osmium", "cat", "--overwrite", "-o", tmp.name, "-f", "osm", pbf], check=True)
        path = tmp.name
    hw = {}
    for _, el in ET.iterparse(path):
        if el.tag == "way":
            for t in el.findall("tag"):
                if t.get("k") == "highway":
                    hw[int(el.get("id"))] = t.get("v")
            el.clear()
        elif el.tag in ("node", "relation"):
            el.clear()
    if tmp:
        os.unlink(tmp.name)
    return hw


def utm_for(lon, lat):
    zone = int((lon + 180) // 6) + 1
    epsg = (32600 if lat >= 0 else 32700) + zone
    return Transformer.from_crs("EPSG:4326", "EPSG:%d" % epsg, always_xy=True).transform


def polys(features, proj):
    out = []
    for f in features:
        if not f.get("geometry"):
            continue
        g = transform(proj, shape(f["geometry"]))
        if not g.is_valid:
            g = g.buffer(0)
        if g.area > 0:
            out.append(g)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("junctions")
    ap.add_argument("case")
    ap.add_argument("--kinds", default="Intersection,Connection,Fork,Terminus")
    ap.add_argument("--all-roads", action="store_true")
    ap.add_argument("--min-iou", type=float, default=0.0, help="pairs below this IoU are not matched")
    a = ap.parse_args()

    ref = json.load(open(os.path.join(a.case, "geometry.json")))["features"]
    kinds = set(a.kinds.split(","))
    inters = [f for f in ref if f["properties"].get("type") == "intersection"
              and f["properties"].get("intersection_kind") in kinds]
    if not a.all_roads:
        hw = way_highways(a.case)
        ends = set()
        for f in ref:
            p = f["properties"]
            if p.get("type") == "road" and p.get("osm_way_ids") and hw.get(p["osm_way_ids"][0]) in CAR:
                ends.update((p["src_i"], p["dst_i"]))
        inters = [f for f in inters if f["properties"]["id"] in ends]
    prod = [f for f in json.load(open(a.junctions))["features"]
            if "MapEdge" not in (f.get("properties", {}).get("kind"), f.get("properties", {}).get("intersection_kind"))]

    allf = inters + prod
    if not allf:
        sys.exit("junction-match: nothing to compare")
    c = shape(allf[0]["geometry"]).centroid
    proj = utm_for(c.x, c.y)
    R, P = polys(inters, proj), polys(prod, proj)

    tree = STRtree(P)
    index = {id(g): i for i, g in enumerate(P)}
    pairs = []
    overlapped = 0
    for ri, r in enumerate(R):
        hit = False
        for p in tree.query(r):
            pi = p if isinstance(p, int) else index[id(p)]
            pg = P[pi]
            ia = r.intersection(pg).area
            if ia > 0:
                hit = True
                pairs.append((ia / r.union(pg).area, ri, pi))
        overlapped += hit
    pairs.sort(reverse=True)
    used_r, used_p, ious = set(), set(), []
    for iou, ri, pi in pairs:
        if iou < a.min_iou or ri in used_r or pi in used_p:
            continue
        used_r.add(ri)
        used_p.add(pi)
        ious.append(iou)
    m = len(ious)
    print("case=%s produced=%d reference=%d matched=%d unmatched_produced=%d unmatched_reference=%d "
          "mean_iou=%.3f matched_iou50=%d reference_overlapped=%d"
          % (os.path.basename(os.path.normpath(a.case)), len(P), len(R), m, len(P) - m, len(R) - m,
             sum(ious) / m if m else 0.0, sum(1 for x in ious if x >= 0.5), overlapped))


if __name__ == "__main__":
    main()
