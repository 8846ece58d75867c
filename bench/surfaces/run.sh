#!/usr/bin/env bash
# Street surfaces: acceptance report and benchmark, on real data, in one run.
#
#   bash bench/surfaces/run.sh            everything (about 5 minutes on 2 cores)
#   DATASETS="osm paris" bash bench/surfaces/run.sh      a subset: osm, cases, paris
#   PEERS=0 bash bench/surfaces/run.sh    without the peer comparison
#   OSM_FILES="liechtenstein.osm.pbf munich.osm.pbf" DATASETS=osm ...   some files of ../shared/data/osm
#   STREETGEN_BENCH_NO_BUILD=1            the streetgen installed for the pg_config on PATH, as it is
#   SURFACES_ONLY=0                       without the street-surfaces-only runs (settings.details false)
#
# Builds and installs streetgen, starts a throwaway cluster, then for every file of
# ../shared/data/osm, every case of ../shared/data/osm2streets and the Paris example graph:
# import (wall time), generate (wall time, peak backend memory), surface_quality, corners by
# status, intersections by status, issues by kind. Then the Neukolln carriageway fidelity against
# the real lane areas, the junction match against osm2streets' stored outputs, and the peers
# (SUMO netconvert, osm2streets-js; bench/peers) on the same OSM files, as time ratios. Last, the
# peers' files and Paris again with settings.details false (street surfaces only: nodes, sections,
# corners, junctions; what issue 3 builds and about what netconvert builds), their ratios too.
# The report goes to stdout and to $OUT/report.md (default build/bench-surfaces).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
out="${OUT:-$repo/build/bench-surfaces}"
datasets="${DATASETS:-osm cases paris}"
peers="${PEERS:-1}"
surfaces_only="${SURFACES_ONLY:-1}"
port="${PORT:-54330}"   # (PORT=... when another cluster holds 54330)
mkdir -p "$out"
report="$out/report.md"
: >"$report"
say() { echo "$*" | tee -a "$report"; }

source "$repo/bench/lib.sh"
bench_cluster "$port"
now() { date +%s.%N; }
since() { awk -v s="$1" -v e="$(now)" 'BEGIN { printf "%.2f", e - s }'; }

# generate MODEL -> prints "seconds peak_kb base_kb": wall time of generate() and the backend's
# peak private memory (its RssAnon, sampled every 20 ms by bench/anon_peak.sh: without shared
# buffers and mapped files such as libraries and the PROJ database, which other processes
# share), and the same before generate() (libraries loaded, model read) - one fresh backend per
# model. Its DEBUG1 messages (the engine's phase times, the blocks' overlays) go to
# $out/generate-MODEL.log.
generate() {
  local model=$1 start
  local kb pid
  kb=$(psql -X -q -At 2>"$out/generate-$model.log" <<SQL
SET client_min_messages = debug1;
SELECT pg_backend_pid() AS pid \gset
\setenv SGPID :pid
\setenv SGPEAK $out/peak-$model.kb
SELECT count(ST_AsEWKB(geom)), streetgen.version() FROM $model.axis \g /dev/null
\! echo \$SGPID; awk '/RssAnon/ { print \$2 }' /proc/\$SGPID/status
\! bash "$repo/bench/anon_peak.sh" \$SGPID "\$SGPEAK" >/dev/null 2>&1 &
\! date +%s.%N
SELECT count(*) FROM streetgen.generate('$model') \g /dev/null
\! date +%s.%N
SQL
)
  grep -h -A2 "ERROR" "$out/generate-$model.log" >&2 || true  # (the DEBUG1 log holds generate's errors too)
  read -r pid base t0 t1 <<<"$(echo $kb)"
  for _ in $(seq 100); do [ -d "/proc/$pid" ] || break; sleep 0.05; done  # (the sampler stops with the backend)
  sleep 0.1
  echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }') $(cat "$out/peak-$model.kb") $base"
}

declare -A import_s import_sections generate_s peak_kb base_kb peer_nc peer_o2
# ours netconvert osm2streets (wall s; a failed peer empty) -> ours / the faster peer, or n/a
ratio_to_peers() {
  awk -v o="$1" -v a="${2:-0}" -v b="${3:-0}" 'BEGIN { m = (a > 0 && (b == 0 || a < b)) ? a : b; if (m > 0) printf "%.2f", o / m; else print "n/a" }'
}
run_dataset() {  # name, import command...
  local name=$1; shift
  local start
  start=$(now)
  "$@" >"$out/import-$name.log" 2>&1 || { echo "import of $name failed: $(tail -3 "$out/import-$name.log")" >&2; return 1; }
  import_s[$name]=$(since "$start")
  import_sections[$name]=$(psql -X -At -c "SELECT count(*) FROM $name.section" 2>/dev/null || echo 0)
  read -r generate_s[$name] peak_kb[$name] base_kb[$name] < <(generate "$name")
}

names=()
if [[ " $datasets " == *" osm "* ]]; then
  for f in "$data"/osm/*; do
    [ -z "${OSM_FILES:-}" ] || [[ " $OSM_FILES " == *" $(basename "$f") "* ]] || continue
    n="$(basename "$f")"; n="${n%%.*}"; n="${n//-/_}"
    run_dataset "$n" "$repo/scripts/streetgen-import" -m "$n" "$f" && names+=("$n")
  done
fi
if [[ " $datasets " == *" cases "* ]]; then
  for d in "$data"/osm2streets/*/; do
    c="$(basename "$d")"; f="$(ls "$d"/input.osm* | head -1)"
    run_dataset "c_$c" "$repo/scripts/streetgen-import" -m "c_$c" "$f" && names+=("c_$c")
  done
fi
if [[ " $datasets " == *" paris "* ]]; then
  load_paris() {  # [model [details]]
    local model=${1:-paris} details=${2:-true}
    psql -X -q -c "SELECT streetgen.create_model('$model', 0)" -c "UPDATE $model.settings SET details = $details"
    ogr2ogr -f PostgreSQL "PG:dbname=$PGDATABASE" "$data/examples/cities/paris.geojson" -nln paris_staging \
      -lco GEOMETRY_NAME=geom -lco SPATIAL_INDEX=NONE --config PG_USE_COPY YES -overwrite
    psql -X -q -v ON_ERROR_STOP=1 -v model="$model" -v staging=paris_staging -f "$repo/bench/surfaces/load-example-graph.sql"
  }
  run_dataset paris load_paris && names+=(paris)
fi

say "# Street surfaces on real data"
say ""
say "streetgen $(psql -X -At -c "SELECT extension || ' (GEOS ' || geos || ', CGAL ' || cgal || ', PostGIS ' || postgis || ')' FROM streetgen.version()"), $(nproc) cores, $(date -u +%Y-%m-%d)."
say "Road data (c) OpenStreetMap contributors, ODbL 1.0; Paris graph from Nishida et al. (ODbL-derived)."
say ""
say "| dataset | axes | nodes | junctions | intersections | invalid | missing | section overlap % | junction overlap % | import s | generate s | peak private MB (before generate) |"
say "|---|---|---|---|---|---|---|---|---|---|---|---|"
for n in "${names[@]}"; do
  row=$(psql -X -At -F '|' -c "
    SELECT (SELECT count(*) FROM $n.axis), q.nodes, q.junctions, q.intersections, q.invalid_geometries,
           q.missing_intersections, round((100 * q.section_overlap_ratio)::numeric, 4),
           round((100 * q.intersection_overlap_area / greatest(q.surface_area, 1e-9))::numeric, 4)
      FROM streetgen.surface_quality('$n') q")
  say "| $n | $row | ${import_s[$n]} | ${generate_s[$n]} | $(( ${peak_kb[$n]:-0} / 1024 )) ($(( ${base_kb[$n]:-0} / 1024 ))) |"
done
say ""
say "Where generate's time goes: the engine's phases in CPU seconds (topology, corners, sections,"
say "lanes and markings, junctions, sidewalks and crossings), then the blocks' overlays per face"
say "(the winding pass, then for the faces it leaves clip with its predicates, union, difference; rounding to the grid, and"
say "the whole call), all CPU seconds, from the DEBUG1"
say "messages of the generate above:"
say ""
say "| dataset | topology | corners | sections | lanes | junctions | sidewalks | blocks: winding | clip | union | difference | rounding | all |"
say "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for n in "${names[@]}"; do
  say "| $n | $(awk '
    /streetgen: surfaces in CPU seconds/ { e = ""; sep = ""; for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+,?$/) { v = $i; sub(",", "", v); e = e sep v; sep = " | " } }
    /streetgen: blocks of/ { b = ""; for (i = 1; i <= NF; i++) if ($i == "winding" || $i == "clips" || $i == "unions" || $i == "differences" || $i == "rounding" || $i == "all") { v = $(i + 1); sub(",", "", v); b = b " | " v } }
    END { print (e == "" ? "n/a | | | | |" : e) (b == "" ? " | n/a | | | | |" : b) }' "$out/generate-$n.log") |"
done
say ""
say "Corners by status, intersections by status, issues by kind:"
say ""
say "| dataset | corners | intersections | issues |"
say "|---|---|---|---|"
for n in "${names[@]}"; do
  corners=$(psql -X -At -c "SELECT string_agg(status || ' ' || c, ', ' ORDER BY c DESC) FROM (SELECT status, count(*) c FROM $n.corner GROUP BY 1) s")
  inters=$(psql -X -At -c "SELECT string_agg(status || ' ' || c, ', ' ORDER BY c DESC) FROM (SELECT status, count(*) c FROM $n.intersection GROUP BY 1) s")
  issues=$(psql -X -At -c "SELECT coalesce(string_agg(kind || ' ' || c, ', ' ORDER BY c DESC), 'none') FROM (SELECT kind, count(*) c FROM $n.issue GROUP BY 1) s")
  say "| $n | $corners | $inters | $issues |"
done
totals=$(psql -X -At -c "SELECT count(*) FROM streetgen.model")
say ""
say "Models: $totals. Acceptance: invalid = 0, missing = 0, section and junction overlap < 0.1 % on every row above."

if [[ " ${names[*]} " == *" c_neukolln "* ]]; then
  say ""
  say "## Fidelity: Neukolln carriageway (truth: lane_area.geojson, OSM + ALKIS)"
  bash "$repo/bench/surfaces/export-surfaces.sh" c_neukolln "$out/neukolln"
  EXCLUDE_SERVICE=1 bash "$repo/bench/surfaces/export-surfaces.sh" c_neukolln "$out/neukolln-main"
  say ""
  say "streetgen, all car roads: $(/usr/bin/python3 "$repo/bench/peers/fidelity-neukoelln.py" "$out/neukolln/streetgen-roads.geojson" "$out/neukolln/streetgen-junctions.geojson" 2>/dev/null)"
  say "streetgen, main roads (no highway=service): $(/usr/bin/python3 "$repo/bench/peers/fidelity-neukoelln.py" "$out/neukolln-main/streetgen-roads.geojson" "$out/neukolln-main/streetgen-junctions.geojson" 2>/dev/null)"
  EXCLUDE_DRIVEWAYS=1 bash "$repo/bench/surfaces/export-surfaces.sh" c_neukolln "$out/neukolln-public"
  say "streetgen, public roads (no service=driveway|parking_aisle: the real carriageway has the public service road but no driveway on a private plot): $(/usr/bin/python3 "$repo/bench/peers/fidelity-neukoelln.py" "$out/neukolln-public/streetgen-roads.geojson" "$out/neukolln-public/streetgen-junctions.geojson" 2>/dev/null)"
fi
if [[ " $datasets " == *" cases "* ]]; then
  say ""
  say "## Junctions against osm2streets' stored outputs (geometry.json)"
  say ""
  matched=0; reference=0; iou_sum=0
  for d in "$data"/osm2streets/*/; do
    c="$(basename "$d")"
    bash "$repo/bench/surfaces/export-surfaces.sh" "c_$c" "$out/cases/$c" >/dev/null 2>&1 || continue
    line=$(/usr/bin/python3 "$repo/bench/peers/junction-match.py" "$out/cases/$c/streetgen-junctions.geojson" "$d" 2>/dev/null || true)
    echo "$c $line" >>"$out/junction-match.txt"
  done
  say "$(awk '{ for (i = 2; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
                 cases++; produced += v["produced"]; reference += v["reference"]; matched += v["matched"]
                 iou += v["mean_iou"] * v["matched"]; iou50 += v["matched_iou50"] }
               END { printf "cases %d: reference junctions %d, produced %d, matched %d, mean IoU of matched %.3f, matched with IoU >= 0.5: %d", cases, reference, produced, matched, (matched ? iou / matched : 0), iou50 }' "$out/junction-match.txt")"
  say "(per case: $out/junction-match.txt)"
fi

if [ "$peers" = 1 ] && [[ " $datasets " == *" osm "* ]]; then
  say ""
  say "## Peers on the same OSM files (wall s; ratio = streetgen import / faster peer)"
  say ""
  say "The import is the whole job: its insert trigger builds every surface of the new axes (the"
  say "generate s column above times a second, whole-model recompute, not part of the job)."
  say ""
  bash "$repo/bench/peers/install-peers.sh" >/dev/null 2>&1
  # netconvert slows down two to three times more than streetgen on a busy machine (README,
  # perf20: Baltimore 0.39 under load 3.3, 0.59-0.62 quiet), so the load goes beside the ratios
  load_before=$(cut -d' ' -f1 /proc/loadavg)
  # memory: both without mapped files or shared memory (the backend: its RssAnon sampled by
  # bench/anon_peak.sh; netconvert: VmHWM - RssFile - RssShmem, read by an exit hook), and
  # netconvert's peak RSS with its libraries (/usr/bin/time)
  mb() { if [ -n "$1" ]; then echo $(( $1 / 1024 )); else echo n/a; fi; }  # kB (or nothing) -> MB
  say "| file | streetgen s | netconvert s | osm2streets s | ratio | streetgen peak private MB | netconvert peak private MB | netconvert peak RSS MB |"
  say "|---|---|---|---|---|---|---|---|"
  for f in liechtenstein.osm.pbf reisterstown.osm.pbf baltimore.osm.pbf munich.osm.pbf campo-grande.osm.gz; do
    n="${f%%.*}"; n="${n//-/_}"
    [ -n "${import_s[$n]:-}" ] || continue
    # (this script's PEERS is 0 or 1: run-peers.sh's is the list of peers)
    lines=$(PEERS="netconvert osm2streets" bash "$repo/bench/peers/run-peers.sh" "$data/osm/$f" "$out/peers/$n" 2>/dev/null || true)
    # a peer that failed (status=fail: it quit early, in a fraction of its real time) is shown as
    # failed and kept out of the ratio
    nc=$(echo "$lines" | sed -n 's/^peer=netconvert .*wall_s=\([0-9.]*\).*status=ok$/\1/p')
    nc_kb=$(echo "$lines" | sed -n 's/^peer=netconvert .*peak_rss_kb=\([0-9]*\).*status=ok$/\1/p')
    nc_priv=$(echo "$lines" | sed -n 's/^peer=netconvert .*private_peak_kb=\([0-9]*\) .*status=ok$/\1/p')
    o2=$(echo "$lines" | sed -n 's/^peer=osm2streets .*wall_s=\([0-9.]*\).*status=ok$/\1/p')
    peer_nc[$n]=${nc:-}; peer_o2[$n]=${o2:-}
    # (an import that left the surfaces to a later generate() would not be the whole job)
    [ "${import_sections[$n]:-0}" -gt 0 ] || { echo "$n: the import built no section" >&2; continue; }
    ours=${import_s[$n]}
    ratio=$(ratio_to_peers "$ours" "${nc:-}" "${o2:-}")
    say "| $f | $ours | ${nc:-failed} | ${o2:-failed} | $ratio | $(( ${peak_kb[$n]:-0} / 1024 )) | $(mb "$nc_priv") | $(mb "$nc_kb") |"
  done
  say ""
  say "Machine load (1-minute average) $load_before before the peers, $(cut -d' ' -f1 /proc/loadavg) after, $(nproc) cores."
  say "Above about 1, the peers slow down more than streetgen and the ratios flatter streetgen: compare on a quiet machine."
fi
# Street surfaces only (settings.details false): the peers' files imported again with
# `streetgen-import -c details=false`, and Paris loaded into a model with it, each then generated
# again in a fresh backend like the full runs above.
if [ "$surfaces_only" = 1 ]; then
  so_rows=()
  for f in liechtenstein.osm.pbf reisterstown.osm.pbf baltimore.osm.pbf munich.osm.pbf campo-grande.osm.gz; do
    n="${f%%.*}"; n="${n//-/_}"
    [ -n "${import_s[$n]:-}" ] || continue
    run_dataset "${n}_surfaces" "$repo/scripts/streetgen-import" -m "${n}_surfaces" -c details=false "$data/osm/$f" || continue
    so_rows+=("$f|$n")
  done
  if [[ " ${names[*]} " == *" paris "* ]]; then
    run_dataset paris_surfaces load_paris paris_surfaces false && so_rows+=("paris|paris")
  fi
  say ""
  say "## Street surfaces only (settings.details false: no lanes, markings, crossings, sidewalks or blocks)"
  say ""
  say "What issue 3 builds (nodes, sections, corners, junctions), about what netconvert builds (junction"
  say "shapes; it also builds lanes). Import = the whole job, as above; generate = a second, whole-model"
  say "recompute; ratio = the import's wall time / the faster peer's (the peers' times are the run above)."
  say ""
  say "| file | import s | generate s | peak private MB | sections | junctions | lanes + sidewalks + blocks | netconvert s | osm2streets s | ratio |"
  say "|---|---|---|---|---|---|---|---|---|---|"
  for row in "${so_rows[@]}"; do
    f=${row%%|*}; n=${row#*|}; m="${n}_surfaces"
    counts=$(psql -X -At -F '|' -c "SELECT (SELECT count(*) FROM $m.section), (SELECT count(*) FROM $m.intersection),
                                             (SELECT count(*) FROM $m.lane) + (SELECT count(*) FROM $m.sidewalk) + (SELECT count(*) FROM $m.block)")
    ratio=$(ratio_to_peers "${import_s[$m]}" "${peer_nc[$n]:-}" "${peer_o2[$n]:-}")
    say "| $f | ${import_s[$m]} | ${generate_s[$m]} | $(( ${peak_kb[$m]:-0} / 1024 )) | $counts | ${peer_nc[$n]:-n/a} | ${peer_o2[$n]:-n/a} | $ratio |"
  done
  say ""
  say "Where the surfaces-only generate's time goes (engine phases, CPU s: topology, corners, sections, lanes, junctions, sidewalks):"
  say ""
  for row in "${so_rows[@]}"; do
    n=${row#*|}; m="${n}_surfaces"
    say "- $m: $(sed -n 's/.*streetgen: surfaces in CPU seconds: //p' "$out/generate-$m.log" | head -1)"
  done
fi
echo "report: $report"
