#!/usr/bin/env sh
# One tracking call per flight, this tree against the last 0.1-API commit
# (950c067): builds that commit's C library in a git worktree under
# target/, builds benches/c_flight.c against each library (gcc -O2, static),
# and runs the two programs alternately, RUNS times (default 3), printing
# each mode's time per photon from both and their ratio (this tree over
# 0.1). R and T must agree between the two to the digits printed.
#
#   scripts/flight_vs_0_1.sh [RUNS]
set -eu
runs=${1:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}
old=$target/flight_0_1
cargo=${CARGO:-cargo}
if [ ! -d "$old" ]; then
  git -C "$root" worktree add --detach "$old" 950c067 >&2
fi
(cd "$old" && CARGO_TARGET_DIR="$old/target" "$cargo" build --release -p scatterkit-capi --quiet >&2)
"$cargo" build --release -p scatterkit-capi --manifest-path "$root/Cargo.toml" --quiet >&2
bin=$target/flight_bench
mkdir -p "$bin"
cc -std=c99 -D_POSIX_C_SOURCE=199309L -O2 -DSK_API_0_1 -I "$old/include" \
  "$root/benches/c_flight.c" -o "$bin/flight_0_1" -lm "$old/target/release/libscatterkit.a" -lpthread -ldl -lm
cc -std=c99 -D_POSIX_C_SOURCE=199309L -O2 -I "$root/include" \
  "$root/benches/c_flight.c" -o "$bin/flight_main" -lm "$target/release/libscatterkit.a" -lpthread -ldl -lm
echo "processor: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), family $(grep -m1 'cpu family' /proc/cpuinfo | cut -d: -f2 | tr -d ' ') model $(grep -m1 '^model\s' /proc/cpuinfo | cut -d: -f2 | tr -d ' ')"
i=1
while [ "$i" -le "$runs" ]; do
  for mode in cb64 cb64z cb32 cbratio grid64 grid32 free64; do
    # "mode seconds ns R T" from each (an exit estimate after it dropped).
    a=$("$bin/flight_0_1" "$mode" | cut -d' ' -f1-5)
    b=$("$bin/flight_main" "$mode" | cut -d' ' -f1-5)
    echo "$a $b" | awk -v run="$i" '{
      printf "run %d %-8s 0.1 %7.1f ns  main %7.1f ns  ratio %.3f  R %s %s  T %s %s\n",
        run, $1, $3, $8, $8 / $3, $4, $9, $5, $10
    }'
  done
  i=$((i + 1))
done
