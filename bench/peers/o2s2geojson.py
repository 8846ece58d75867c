#!/usr/bin/python3
"""Post-process osm2streets' own exports into the benchmark's two files (WGS84).

usage: o2s2geojson.py PREFIX ROADS_OUT JUNCTIONS_OUT [FULL_ROADS_OUT]

Car roads only (as netconvert with --keep-edges.by-vclass passenger): a road is
kept when it has a Driving or Bus lane. Its polygon is the union of its
carriageway lanes (every lane except Sidewalk, Footway, SharedUse: curb to
curb). FULL_ROADS_OUT (optional) gets osm2streets' whole road polygon
(sidewalks included) for the same roads. Junctions: every osm2streets
intersection polygon that is an end of a kept road.
Prints: roads=<n> junctions=<n>
"""
import json
import sys
from collections import defaultdict

from shapely.geometry import shape, mapping
from shapely.ops import unary_union

NOT_CARRIAGEWAY = {"Sidewalk", "Footway", "SharedUse"}
CAR = {"Driving", "Bus"}


def fc(features):
    return {"type": "FeatureCollection", "features": features}


def main():
    prefix, roads_out, junctions_out = sys.argv[1:4]
    full_out = sys.argv[4] if len(sys.argv) > 4 else None
    plain = json.load(open(prefix + ".plain.geojson"))["features"]
    lanes = json.load(open(prefix + ".lanes.geojson"))["features"]
    tags = json.load(open(prefix + ".tags.json"))

    by_road = defaultdict(list)
    for f in lanes:
        by_road[f["properties"]["road"]].append(f)

    roads = [f for f in plain if f["properties"]["type"] == "road"]
    inters = [f for f in plain if f["properties"]["type"] == "intersection"]
    # toGeojsonPlain has no road id; roads come in the same order as lane polygons' "road" ids
    # (both iterate the network's BTreeMap of roads). Match by osm_way_ids + order to be safe.
    road_ids = sorted(by_road)
    if len(road_ids) != len(roads):
        raise SystemExit("o2s2geojson: %d roads but lanes for %d" % (len(roads), len(road_ids)))
    out_roads, full_roads, ends = [], [], set()
    for idx, f in enumerate(roads):
        rid = f["properties"].get("id", road_ids[idx] if idx < len(road_ids) else None)
        ls = by_road.get(rid, [])
        if ls and ls[0]["properties"]["osm_way_ids"] != f["properties"]["osm_way_ids"]:
            raise SystemExit("o2s2geojson: road/lane order mismatch at road %s" % rid)
        types = [l["properties"]["type"] for l in ls]
        if not CAR.intersection(types):
            continue
        carriage = [shape(l["geometry"]).buffer(0) for l in ls if l["properties"]["type"] not in NOT_CARRIAGEWAY]
        geom = unary_union(carriage)
        if geom.is_empty:
            continue
        way = f["properties"]["osm_way_ids"]
        props = {"road": rid, "osm_way_ids": way, "highway": tags.get(str(way[0])) if way else None,
                 "src_i": f["properties"]["src_i"], "dst_i": f["properties"]["dst_i"],
                 "lanes": types, "width_m": round(sum(l["properties"]["width"] for l in ls
                                                      if l["properties"]["type"] not in NOT_CARRIAGEWAY), 3)}
        out_roads.append({"type": "Feature", "properties": props, "geometry": mapping(geom)})
        full_roads.append({"type": "Feature", "properties": props, "geometry": f["geometry"]})
        ends.update((f["properties"]["src_i"], f["properties"]["dst_i"]))
    out_j = []
    for f in inters:
        p = f["properties"]
        if p["id"] not in ends or f["geometry"] is None:
            continue
        out_j.append({"type": "Feature", "geometry": f["geometry"],
                      "properties": {"id": p["id"], "kind": p.get("intersection_kind"),
                                     "control": p.get("control"), "osm_node_ids": p.get("osm_node_ids")}})
    json.dump(fc(out_roads), open(roads_out, "w"))
    json.dump(fc(out_j), open(junctions_out, "w"))
    if full_out:
        json.dump(fc(full_roads), open(full_out, "w"))
    print("roads=%d junctions=%d" % (len(out_roads), len(out_j)))


if __name__ == "__main__":
    main()
