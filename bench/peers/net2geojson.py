#!/usr/bin/python3
"""Convert a SUMO .net.xml (netconvert output) into road and junction polygons (WGS84 GeoJSON).

usage: net2geojson.py NET.xml ROADS_OUT JUNCTIONS_OUT

- Coordinates: net x,y minus <location netOffset> are in <location projParameter>
  (UTM for OSM input); pyproj turns them back into lon/lat.
- Junctions: every non-internal <junction> with a shape of >= 3 points, as a polygon
  (buffer(0) to repair self-touching shapes; empty ones are skipped and counted).
- Roads: every normal <edge> (no function=internal/crossing/walkingarea); each lane's
  shape buffered by width/2 (flat caps, mitre joins), unioned per edge. A lane
  without width attribute has SUMO's default width 3.2 m.
Prints: roads=<n> junctions=<n> skipped_junctions=<n>
"""
import json
import sys
import xml.etree.ElementTree as ET

from pyproj import Transformer
from shapely.geometry import LineString, Polygon, mapping
from shapely.ops import transform, unary_union

DEFAULT_LANE_WIDTH = 3.2


def parse_shape(s):
    pts = []
    for p in s.split():
        c = p.split(",")
        pts.append((float(c[0]), float(c[1])))
    return pts


def main():
    net, roads_out, junctions_out = sys.argv[1:4]
    to_wgs = None
    off = (0.0, 0.0)
    roads, junctions = [], []
    skipped = 0
    edge = None
    lanes = []

    def project(geom):
        ox, oy = off
        return transform(lambda x, y, z=None: to_wgs.transform(x - ox, y - oy), geom)

    for ev, el in ET.iterparse(net, events=("start", "end")):
        tag = el.tag
        if ev == "start":
            if tag == "edge":
                edge = el
                lanes = []
            continue
        if tag == "location":
            ox, oy = (float(v) for v in el.get("netOffset").split(","))
            off = (ox, oy)
            to_wgs = Transformer.from_crs(el.get("projParameter"), "EPSG:4326", always_xy=True)
        elif tag == "lane" and edge is not None:
            lanes.append((el.get("shape"), float(el.get("width", DEFAULT_LANE_WIDTH))))
        elif tag == "edge":
            fn = el.get("function")
            if fn is None or fn == "normal":
                polys = []
                for shp, w in lanes:
                    pts = parse_shape(shp)
                    if len(pts) < 2:
                        continue
                    polys.append(LineString(pts).buffer(w / 2.0, cap_style=2, join_style=2, mitre_limit=3.0))
                g = unary_union(polys) if polys else None
                if g is not None and not g.is_empty:
                    roads.append({"type": "Feature", "geometry": mapping(project(g)), "properties": {
                        "id": el.get("id"), "from": el.get("from"), "to": el.get("to"),
                        "type": el.get("type"), "name": el.get("name"), "lanes": len(lanes),
                        "width_m": round(sum(w for _, w in lanes), 3)}})
            edge = None
            el.clear()
        elif tag == "junction":
            if el.get("type") != "internal":
                pts = parse_shape(el.get("shape", ""))
                g = Polygon(pts).buffer(0) if len(pts) >= 3 else None
                if g is None or g.is_empty:
                    skipped += 1
                else:
                    junctions.append({"type": "Feature", "geometry": mapping(project(g)), "properties": {
                        "id": el.get("id"), "type": el.get("type"),
                        "radius": el.get("radius")}})
            el.clear()
        elif tag in ("connection", "request", "tlLogic", "roundabout"):
            el.clear()

    json.dump({"type": "FeatureCollection", "features": roads}, open(roads_out, "w"))
    json.dump({"type": "FeatureCollection", "features": junctions}, open(junctions_out, "w"))
    print("roads=%d junctions=%d skipped_junctions=%d" % (len(roads), len(junctions), skipped))


if __name__ == "__main__":
    main()
