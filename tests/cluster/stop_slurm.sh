#!/usr/bin/env bash
# Stop the daemons that start_slurm.sh started (listed in $STARTED_FILE), by the PIDs in
# their pidfiles, last started first; daemons that were already running are left alone.
set -u
STARTED_FILE="${STARTED_FILE:-/run/slurm/kinetic-started}"
[ -f "$STARTED_FILE" ] || exit 0
for pf in $(tac "$STARTED_FILE"); do
  [ -f "$pf" ] || continue
  pid=$(cat "$pf")
  if kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid"
    for _ in $(seq 1 60); do kill -0 "$pid" 2>/dev/null || break; sleep 0.5; done
    if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid"; fi
    echo "stopped $pf (pid $pid)"
  fi
  rm -f "$pf"
done
rm -f "$STARTED_FILE"
