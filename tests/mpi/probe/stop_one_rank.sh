#!/bin/sh
# stop_one_rank.sh <mpiexec> <np> <water_drop> <out>: SIGINT to one rank of a distributed
# water_drop run only. The stop poll is collective (time loop, before every RHS): every rank
# must stop at the same step, the run exit with 130, say "stopped by signal 2" and record
# "stopped" in run.json; its checkpoint (the whole run's, rank 0 writes it) continues on 3 ranks.
MPIEXEC=$1 NP=$2 DROP=$3 OUT=$4
rm -rf "$OUT" "$OUT.log" "$OUT.restarted" "$OUT.restarted.log"
"$MPIEXEC" --oversubscribe --allow-run-as-root -np "$NP" "$DROP" --no-render --threads 1 --scheme delta-sph \
  --cleaning on --out "$OUT" > "$OUT.log" 2>&1 &
RUN=$!
i=0
until [ -f "$OUT/cleaned/diagnostics.csv" ] || [ $i -ge 600 ]; do sleep 0.1; i=$((i + 1)); done  # the loop runs
RANK=$(pgrep -P "$RUN" | tail -n 1)
[ -n "$RANK" ] || { echo "no rank process of $RUN"; cat "$OUT.log"; exit 1; }
kill -INT "$RANK"
wait "$RUN"
rc=$?
cat "$OUT.log"
[ "$rc" -eq 130 ] || { echo "exit code $rc, expected 130"; exit 1; }
grep -q "cleaned run stopped by signal 2 at t=" "$OUT.log" || { echo "no stop message"; exit 1; }
grep -q '"outcome": "stopped"' "$OUT/run.json" || { echo "run.json: not stopped"; exit 1; }
grep -q "continue with --restart" "$OUT.log" || { echo "no checkpoint"; exit 1; }
# on to 0.0005 past the stop (wherever the signal found the run)
T_STOP=$(sed -n 's/.*cleaned run stopped by signal 2 at t=\([0-9.e+-]*\);.*/\1/p' "$OUT.log" | head -n 1)
T_END=$(awk -v t="$T_STOP" 'BEGIN { printf "%.6g", t + 0.0005 }')
"$MPIEXEC" --oversubscribe --allow-run-as-root -np 3 "$DROP" --restart "$OUT/cleaned/checkpoint.bin" --t-end "$T_END" \
  --out "$OUT.restarted" > "$OUT.restarted.log" 2>&1 || { cat "$OUT.restarted.log"; echo "the 3-rank restart failed"; exit 1; }
echo "every rank stopped (exit 130) at t = $T_STOP; the checkpoint continued on 3 ranks to t = $T_END"
