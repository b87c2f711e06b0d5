#!/usr/bin/env bash
# Start a study under mpirun, SIGKILL one worker rank once the CSV holds at least MIN_ROWS rows,
# and wait for mpirun to end. Used by the test sweep-mpi/resume-after-kill.
# usage: kill_worker.sh ROLLCON STUDY OUTPUT_DIR CSV MIN_ROWS
# Prints "killed PID rows-at-kill ROWS mpirun-status STATUS"; exit 0 when a worker was killed,
# 1 when the study ended before MIN_ROWS rows or no worker rank was found.
set -u
rollcon=$1 study=$2 output=$3 csv=$4 min_rows=$5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun --oversubscribe -np 3 "$rollcon" sweep "$study" --output "$output" --quiet --no-map \
    > "$output/mpirun.log" 2>&1 &
launcher=$!
rows=0
for _ in $(seq 1 600); do
    rows=$(($(wc -l < "$csv" 2> /dev/null || echo 1) - 1))
    ((rows >= min_rows)) && break
    kill -0 "$launcher" 2> /dev/null || break
    sleep 0.05
done
victim=""
for pid in $(pgrep -f -- "sweep $study --output $output"); do
    if tr '\0' '\n' < "/proc/$pid/environ" 2> /dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
        victim=$pid
        break
    fi
done
if [[ -z "$victim" ]] || ((rows < min_rows)); then
    wait "$launcher"
    echo "no worker killed: rows $rows, worker '$victim'"
    exit 1
fi
kill -KILL "$victim"
wait "$launcher"
status=$?
echo "killed $victim rows-at-kill $rows mpirun-status $status"
exit 0
