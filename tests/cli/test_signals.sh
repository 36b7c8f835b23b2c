#!/bin/sh
# test_signals.sh — a run stopped by signals leaves nothing behind.
#
# SIGNAL_RUNS runs (default 100) in a row, alternating a `render` (which
# writes an EXR and a PNG through temporary files) and a `scene-plan`
# (stdout only).  Each run is sent, after a random delay inside its running
# time, one signal or two in quick succession (what `timeout` does: one to
# the child, one to its group; or Ctrl-C twice): TERM, TERM+TERM, INT+INT,
# INT+TERM, HUP+TERM, TERM+INT, sent back to back by the shell (microseconds
# apart), 0–20 ms apart, or by `timeout` itself.  After each run:
#   - no temporary file (*.tmp.*) is left in the output folder;
#   - each output file is either absent or complete (its format's magic
#     number; the run may have committed it just before the signal);
#   - a run that was stopped printed nothing on stdout (no half result), and
#     one that finished exited 0 with its result: once a run has begun to
#     print its result it holds stop signals and finishes (cli_signals_commit).
# The delays are drawn from a fixed seed, so a failure can be replayed.
. "$(dirname "$0")/lib.inc"

RUNS=${SIGNAL_RUNS:-100}
D="$TMP/sig"
mkdir -p "$D"
RENDER="render --scene sphere-plane --res 12 --light cie-clear:0.5,0.3 --rays 512 --order 5 --width 320 --height 240 --quiet --format json"
PLAN="scene-plan --scene sphere-plane --res 6 --light cie-clear:0.5,0.3 --budget 0.05 --vertices 60 --ref-samples 4096 --quiet --format json"

# running time of each command, to spread the signals over it
start=$(date +%s.%N); $SHLAB $RENDER --out "$D/t.exr" --png "$D/t.png" >/dev/null 2>&1; t_render=$(echo "$start $(date +%s.%N)" | awk '{ print $2 - $1 }')
start=$(date +%s.%N); $SHLAB $PLAN >/dev/null 2>&1; t_plan=$(echo "$start $(date +%s.%N)" | awk '{ print $2 - $1 }')
rm -f "$D"/*

# magic: EXR 76 2f 31 01, PNG 89 50 4e 47
magic_ok() {
    [ ! -e "$1" ] && return 0
    m=$(od -An -tx1 -N4 "$1" | tr -d ' \n')
    case "$2" in exr) [ "$m" = 762f3101 ] ;; png) [ "$m" = 89504e47 ] ;; esac
}


fails=0 stopped=0 finished=0
i=0
while [ "$i" -lt "$RUNS" ]; do
    # fixed-seed draws: delay fraction, signal pattern, gap
    set -- $(awk -v s="$i" 'BEGIN { srand(1000 + s); print rand(), int(rand() * 6), rand() * 0.02, int(rand() * 4) }')
    frac=$1 pat=$2 gap=$3 how=$4 # how: 0, 1 back to back; 2 with the gap; 3 by timeout
    case $pat in
    0) s1=TERM s2= ;; 1) s1=TERM s2=TERM ;; 2) s1=INT s2=INT ;;
    3) s1=INT s2=TERM ;; 4) s1=HUP s2=TERM ;; *) s1=TERM s2=INT ;;
    esac
    if [ $((i % 2)) = 0 ]; then what=render dur=$t_render; else what=scene-plan dur=$t_plan; fi
    delay=$(awk -v f="$frac" -v d="$dur" 'BEGIN { printf "%.3f", f * d * 0.95 }')
    if [ "$what" = render ]; then args="$RENDER --out $D/r.exr --png $D/r.png"; else args=$PLAN; fi
    if [ "$how" = 3 ]; then
        s2=; gap=
        # timeout sends s1 to the child, then to its own process group (itself);
        # --preserve-status: the child's own status (124 would only say that
        # the timer fired, also when the child had begun its result and finished)
        timeout --preserve-status -s "$s1" "$delay" $SHLAB $args >"$D/stdout" 2>"$D/stderr"; rc=$?
    else
        # a non-interactive shell starts background jobs with SIGINT ignored
        # (and shlab keeps an ignored signal ignored): restore it
        env --default-signal=INT $SHLAB $args >"$D/stdout" 2>"$D/stderr" &
        pid=$!
        sleep "$delay"
        if [ -z "$s2" ]; then kill -s "$s1" "$pid" 2>/dev/null
        elif [ "$how" = 2 ]; then kill -s "$s1" "$pid" 2>/dev/null; sleep "$gap"; kill -s "$s2" "$pid" 2>/dev/null
        else kill -s "$s1" "$pid" 2>/dev/null; kill -s "$s2" "$pid" 2>/dev/null; fi
        wait "$pid" 2>/dev/null; rc=$?
    fi
    left=$(ls "$D" | grep '\.tmp\.' || true)
    bad=""
    [ -z "$left" ] || bad="temporary files left: $left"
    magic_ok "$D/r.exr" exr || bad="$bad; r.exr incomplete"
    magic_ok "$D/r.png" png || bad="$bad; r.png incomplete"
    if [ "$rc" = 0 ]; then
        finished=$((finished + 1))
        [ -s "$D/stdout" ] || bad="$bad; finished without a result"
    else
        stopped=$((stopped + 1))
        [ "$rc" -gt 128 ] || bad="$bad; exit $rc (not a signal): $(head -c 200 "$D/stderr")"
        [ ! -s "$D/stdout" ] || bad="$bad; a stopped run printed $(wc -c <"$D/stdout") bytes"
    fi
    if [ -n "$bad" ]; then
        notok "run $i ($what, $s1${s2:++$s2} how $how after $delay s): $bad"
        fails=$((fails + 1))
    fi
    rm -f "$D"/*
    i=$((i + 1))
done
[ "$fails" = 0 ] && ok "$RUNS signalled runs ($stopped stopped, $finished finished first): nothing left behind"
[ "$stopped" -ge $((RUNS / 2)) ] && ok "most runs were stopped by the signals ($stopped of $RUNS)" ||
    notok "most runs were stopped by the signals (only $stopped of $RUNS)"
