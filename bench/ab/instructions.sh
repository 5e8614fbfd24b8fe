#!/bin/sh
# bench/ab/instructions.sh [new|old]: instructions per ray (callgrind) of each ray set, bunny and 1M
side=${1:-new}
for m in bunny big; do for s in 1 2 3; do
  out=$(valgrind --tool=callgrind --toggle-collect=${side}_trace --callgrind-out-file=/dev/null build/ab/ab --only $side --mesh $m --set $s --reps 1 2>&1)
  n=$(echo "$out" | awk '/rays done/{print $2}'); ir=$(echo "$out" | awk '/Collected/{print $4}')
  echo "$side $m set$s: $(echo "$ir / $n" | bc) instr/ray"
done; done
