#!/usr/bin/python3
"""Area fidelity of street surfaces against the real Neukölln carriageway.

usage: fidelity-neukoelln.py ROADS.geojson JUNCTIONS.geojson [--clip MODE] [--case DIR] [--truth FILE]

Produced surface = union(roads + junctions). Truth = lane_area.geojson (carriageway,
curbs from OSM + ALKIS). Both are clipped to the same area and compared in UTM 33N
(EPSG:32633).

Clip area (MODE):
  auto        DIR/boundary.json if it exists, else 'roads-hull' (default; the neukolln
              case has no boundary.json)
  boundary    DIR/boundary.json (error if missing)
  hull        convex hull of all nodes of all <way>s of DIR/input.osm
  bbox        bounding box of the same nodes
  roads-hull  convex hull of the nodes of the car-road ways (highway=motorway..residential,
              living_street, service, unclassified, *_link) of DIR/input.osm
  highway-hull convex hull of the nodes of all highway=* ways (footways too)
Inputs in WGS84 (GeoJSON default). Prints one line:
  clip=<mode> area_iou=<x> truth_covered=<share of truth covered> produced_area_m2=<a>
  truth_area_m2=<b> produced_in_truth=<share of produced area on real carriageway>
  intersection_m2=<i> clip_area_m2=<c>
(produced_area_m2 and truth_area_m2 are inside the clip area).
"""
import argparse
import json
import os
import sys
import xml.etree.ElementTree as ET

from pyproj import Transformer
from shapely.geometry import MultiPoint, Polygon, box, shape
from shapely.ops import transform, unary_union

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "data"))
CAR = {"motorway", "trunk", "primary", "secondary", "tertiary", "unclassified", "residential",
       "living_street", "service", "motorway_link", "trunk_link", "primary_link",
       "secondary_link", "tertiary_link", "road"}

to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32633", always_xy=True).transform


def load_union(path):
    d = json.load(open(path))
    geoms = []
    for f in d.get("features", []):
        if f.get("geometry"):
            g = shape(f["geometry"])
            if not g.is_valid:
                g = g.buffer(0)
            geoms.append(transform(to_utm, g))
    return unary_union(geoms) if geoms else Polygon()


def osm_points(path, keep):
    nodes, pts = {}, []
    for _, el in ET.iterparse(path):
        if el.tag == "node":
            nodes[el.get("id")] = (float(el.get("lon")), float(el.get("lat")))
            el.clear()
        elif el.tag == "way":
            hw = None
            for t in el.findall("tag"):
                if t.get("k") == "highway":
                    hw = t.get("v")
            if keep(hw):
                pts.extend(nodes[n.get("ref")] for n in el.findall("nd") if n.get("ref") in nodes)
            el.clear()
    return [to_utm(x, y) for x, y in pts]


def clip_area(mode, case):
    bpath = os.path.join(case, "boundary.json")
    if mode == "auto":
        mode = "boundary" if os.path.exists(bpath) else "roads-hull"
    if mode == "boundary":
        d = json.load(open(bpath))
        feats = d["features"] if "features" in d else [d]
        g = unary_union([shape(f["geometry"] if "geometry" in f else f) for f in feats])
        return mode, transform(to_utm, g)
    osm = os.path.join(case, "input.osm")
    keep = {"roads-hull": lambda hw: hw in CAR, "highway-hull": lambda hw: hw is not None}.get(mode, lambda hw: True)
    pts = osm_points(osm, keep)
    if mode in ("hull", "roads-hull", "highway-hull"):
        return mode, MultiPoint(pts).convex_hull
    if mode == "bbox":
        return mode, box(*MultiPoint(pts).bounds)
    sys.exit("unknown clip mode " + mode)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("roads")
    ap.add_argument("junctions")
    ap.add_argument("--clip", default="auto", choices=["auto", "boundary", "hull", "bbox", "roads-hull", "highway-hull"])
    ap.add_argument("--case", default=os.path.join(DATA, "osm2streets", "neukolln"))
    ap.add_argument("--truth", default=os.path.join(DATA, "truth", "berlin-neukoelln", "lane_area.geojson"))
    a = ap.parse_args()

    mode, clip = clip_area(a.clip, a.case)
    produced = unary_union([load_union(a.roads), load_union(a.junctions)]).intersection(clip)
    truth = load_union(a.truth).intersection(clip)
    inter = produced.intersection(truth).area
    union = produced.union(truth).area
    iou = inter / union if union > 0 else 0.0
    cov = inter / truth.area if truth.area > 0 else 0.0
    prec = inter / produced.area if produced.area > 0 else 0.0
    print("clip=%s area_iou=%.4f truth_covered=%.4f produced_area_m2=%.0f truth_area_m2=%.0f "
          "produced_in_truth=%.4f intersection_m2=%.0f clip_area_m2=%.0f"
          % (mode, iou, cov, produced.area, truth.area, prec, inter, clip.area))


if __name__ == "__main__":
    main()
