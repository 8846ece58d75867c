#!/usr/bin/env bash
# anon_peak.sh PID FILE: samples the private anonymous memory of process PID (RssAnon, kB) every
# 20 ms until it exits, and keeps the highest value in FILE.
#
# Why not VmHWM minus the shared and file-backed memory read at the end: a PostgreSQL backend
# keeps touching shared buffers after its own peak (storing a whole city's rows), so its total
# resident peak comes at the end, and that difference gave its private memory at the end rather
# than at its peak (Reisterstown: 62 MB read, against 85 MB of RssAnon in the engine).
pid=$1 file=$2 peak=0
echo 0 >"$file"
while [ -r "/proc/$pid/status" ]; do
  while read -r key value _; do
    if [ "$key" = "RssAnon:" ]; then
      if [ "$value" -gt "$peak" ]; then peak=$value; echo "$peak" >"$file"; fi
      break
    fi
  done <"/proc/$pid/status" 2>/dev/null || break
  sleep 0.02
done
