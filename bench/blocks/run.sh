#!/usr/bin/env bash
# City blocks: the C++ overlay (src/core/streets/blocks.cpp) against the SQL one it replaced
# (bench/blocks/sql-peer.sql), in the same run, on Liechtenstein (OSM) and the Paris example graph.
#
#   bash bench/blocks/run.sh                    build, own cluster, load both, 3 rounds
#   ROUNDS=5 MODELS=liechtenstein bash bench/blocks/run.sh
#   REUSE=1 bash bench/blocks/run.sh            the database of PGHOST/PGPORT/PGDATABASE as it is
#                                               (models already loaded; no build, no cluster)
#   PORT=54332                                  the throwaway cluster's port
#   WHAT=blocks                                 the blocks alone (default: "blocks generate")
#
# Per model and round, alternating which goes first: the blocks alone (_compute_blocks of the
# whole model, C++ vs SQL), and a whole streetgen.generate() with either (the SQL one swapped in
# inside a transaction that is rolled back). Prints the medians and the ratios SQL / C++, and
# checks that both give the same blocks (same keys, axes and kind; geometry within 1e-6 m).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
data="${STREETGEN_SHARED_DATA:-$repo/../shared/data}"
rounds="${ROUNDS:-3}"
models="${MODELS:-liechtenstein paris}"
what_list="${WHAT:-blocks generate}"
source "$repo/bench/lib.sh"
if [ "${REUSE:-0}" != 1 ]; then
  bench_cluster "${PORT:-54332}"
  for m in $models; do
    case "$m" in
      paris)
        psql -X -q -c "SELECT streetgen.create_model('paris', 0)"
        ogr2ogr -f PostgreSQL "PG:dbname=$PGDATABASE" "$data/examples/cities/paris.geojson" -nln paris_staging \
          -lco GEOMETRY_NAME=geom -lco SPATIAL_INDEX=NONE --config PG_USE_COPY YES -overwrite
        psql -X -q -v ON_ERROR_STOP=1 -v model=paris -v staging=paris_staging -f "$repo/bench/surfaces/load-example-graph.sql" ;;
      *) "$repo/scripts/streetgen-import" -m "$m" "$data/osm/$m.osm.pbf" >/dev/null ;;
    esac
  done
fi
psql -X -q -v ON_ERROR_STOP=1 -v target=blocks_peer -f "$repo/bench/blocks/sql-peer.sql"

# ms MODEL WHICH WHAT: wall time (ms) of one run, as the server sees it (clock_timestamp around it).
ms() {
  local model=$1 which=$2 what=$3 sql
  case "$what/$which" in
    blocks/cxx) sql="PERFORM streetgen._compute_blocks('$model', NULL);" ;;
    blocks/sql) sql="PERFORM blocks_peer._compute_blocks('$model', NULL);" ;;
    generate/*) sql="PERFORM count(*) FROM streetgen.generate('$model');" ;;
  esac
  {
    echo "BEGIN;"
    [ "$what/$which" = generate/sql ] && echo '\set target streetgen' && echo "\\i $repo/bench/blocks/sql-peer.sql"
    echo "DO \$\$ DECLARE t timestamptz := clock_timestamp(); BEGIN $sql"
    echo "RAISE WARNING 'ms=%', round(1000 * extract(epoch FROM clock_timestamp() - t)); END \$\$;"
    echo "ROLLBACK;"
  } | psql -X -q -v ON_ERROR_STOP=1 2>&1 >/dev/null | sed -n 's/.*ms=\([0-9]*\).*/\1/p'
}
median() { tr ' ' '\n' | grep . | sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "streetgen $(psql -X -At -c "SELECT extension || ' (GEOS ' || geos || ', PostGIS ' || postgis || ')' FROM streetgen.version()"), $(nproc) cores, $(date -u +%Y-%m-%d), $rounds rounds, medians"
for m in $models; do
  faces=$(psql -X -At -c "SELECT count(*) FROM $m.block")
  declare -A t=()
  for r in $(seq 1 "$rounds"); do
    order="cxx sql"; [ $((r % 2)) = 0 ] && order="sql cxx"
    for what in $what_list; do
      for which in $order; do t[$what/$which]+=" $(ms "$m" "$which" "$what")"; done
    done
  done
  # Same blocks from both (in one session: the work table is per session).
  same=$(psql -X -At -v ON_ERROR_STOP=1 <<SQL | tail -1
SELECT streetgen._compute_blocks('$m', NULL);
CREATE TEMP TABLE cxx AS SELECT * FROM pg_temp._sg_blocks;
SELECT blocks_peer._compute_blocks('$m', NULL);
SELECT format('%s blocks; missing %s, extra %s, other axes or kind %s, geometry farther than 1e-6 m %s, not ST_Equals %s',
              count(*), count(*) FILTER (WHERE c.id IS NULL), count(*) FILTER (WHERE s.id IS NULL),
              count(*) FILTER (WHERE c.axis_ids <> s.axis_ids OR c.kind <> s.kind),
              count(*) FILTER (WHERE (c.geom IS NULL) <> (s.geom IS NULL) OR ST_HausdorffDistance(c.geom, s.geom) > 1e-6),
              count(*) FILTER (WHERE NOT ST_Equals(c.geom, s.geom)))
  FROM cxx c FULL JOIN pg_temp._sg_blocks s ON s.id = c.id;
SQL
)
  for what in $what_list; do
    c=$(echo "${t[$what/cxx]}" | median); q=$(echo "${t[$what/sql]}" | median)
    echo "$m ($faces faces): $what with SQL blocks $q ms, with C++ blocks $c ms, ratio SQL / C++ $(awk -v a="$q" -v b="$c" 'BEGIN { printf "%.2f", a / b }'); runs (ms): SQL${t[$what/sql]}; C++${t[$what/cxx]}"
  done
  echo "$m: same result: $same"
  unset t
done
