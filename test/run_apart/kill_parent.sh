#!/usr/bin/env bash
# rollcon test helper (the test suite run-apart): start `rollcon ARGS...` with its
# output in OUT.out and OUT.err, wait (up to 60 s) until it has forked the child process that
# runs a user's routine (a child running the same program), send SIGNAL to rollcon itself,
# and report on stdout how the child fared: "child-gone MS" (it was gone MS milliseconds after
# the signal) or "child-alive" (still there 5 s after), or "no-child" when none appeared.
# usage: kill_parent.sh SIGNAL OUT PROGRAM ARGS...
# (SIGINT is not one to send here: a job in the background of a script ignores it. Ctrl-C at a
# terminal sends it to the whole process group, the child included.)
set -u
signal=$1 out=$2
shift 2
"$@" > "$out.out" 2> "$out.err" &
parent=$!
child=""
for _ in $(seq 600); do
    exe=$(readlink "/proc/$parent/exe" 2> /dev/null)
    for pid in $(pgrep -P "$parent" 2> /dev/null); do
        if [[ "$(readlink "/proc/$pid/exe" 2> /dev/null)" == "$exe" ]]; then child=$pid; fi
    done
    [[ -n "$child" ]] && break
    sleep 0.1
done
if [[ -z "$child" ]]; then
    echo "no-child"
    kill -KILL "$parent" 2> /dev/null
    exit 0
fi
sleep 0.5                        # the child is in the routine's endless call by now
kill "-$signal" "$parent"
start=$(date +%s%N)
for _ in $(seq 500); do
    state=$(awk '{print $3}' "/proc/$child/stat" 2> /dev/null)
    if [[ -z "$state" || "$state" == Z ]]; then
        echo "child-gone $(( ($(date +%s%N) - start) / 1000000 ))"
        wait "$parent" 2> /dev/null
        exit 0
    fi
    sleep 0.01
done
echo "child-alive"
kill -KILL "$child" 2> /dev/null
exit 0
