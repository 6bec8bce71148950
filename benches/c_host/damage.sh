#!/usr/bin/env bash
# The damage outputs' cost from a C host (benches/c_host/hunting.c): the hunting wheelset of
# hunting.sh stepped with wearModel 0 and with a wear model (1 USFD, 2 Archard-KTH), the two runs
# of each pair back to back and the pairs repeated ROUNDS times, so that the machine's load moves
# both alike. Prints per configuration the thread CPU medians [µs per step] of both and the
# median over the rounds of their ratio (docs/performance.md, "Damage outputs").
# Needs the packed FMU: `cargo run --release -p fmu-pack` first.
# Usage: benches/c_host/damage.sh [STEPS] [ROUNDS] [WEAR]   (defaults 5 000, 5, 1)
set -euo pipefail
cd "$(dirname "$0")/../.."
STEPS="${1:-5000}"
ROUNDS="${2:-5}"
WEAR="${3:-1}"
# shellcheck source=benches/c_host/fmu_unpack.sh
. benches/c_host/fmu_unpack.sh normalModel tangentialModel planarPatch wearModel Qleft Qright y \
  yaw vx vy yawRate omega
gcc -O2 -std=c99 -o "$WORK/hunting" benches/c_host/hunting.c -ldl -lm
cpu_median() { "$WORK/hunting" "$LIB" "$GUID" "$URI" hunting "$STEPS" "$1" "$2" "$3" "$4" $VRS \
  | awk '{print $5}'; }
echo "wearModel $WEAR against 0, hunting wheelset, $STEPS steps x $ROUNDS rounds, CPU median µs per step"
printf "%-32s %8s %8s %8s\n" configuration off on ratio
# name normalModel tangentialModel planarPatch
# DAMAGE_CONFIGS (the same form, ";"-separated) replaces the list.
CONFIGS=(
  "Hertz+FASTSIM 1 1 0"
  "ANALYN+FASTSIM 6 1 0"
  "ANALYN+FaStrip-coupled,planar 6 5 1"
  "coupled+FASTSIM 7 1 0"
  "coupled+FaStrip-coupled 7 5 0"
)
if [ -n "${DAMAGE_CONFIGS:-}" ]; then IFS=';' read -r -a CONFIGS <<< "$DAMAGE_CONFIGS"; fi
for C in "${CONFIGS[@]}"; do
  read -r NAME N T P <<< "$C"
  OFF=() ON=() RATIOS=()
  for _ in $(seq "$ROUNDS"); do
    A=$(cpu_median "$N" "$T" "$P" 0)
    B=$(cpu_median "$N" "$T" "$P" "$WEAR")
    OFF+=("$A") ON+=("$B") RATIOS+=("$(python3 -c "print($B / $A)")")
  done
  python3 - "$NAME" "${#OFF[@]}" "${OFF[@]}" "${ON[@]}" "${RATIOS[@]}" <<'PY'
import statistics, sys
name, n = sys.argv[1], int(sys.argv[2])
v = [float(x) for x in sys.argv[3:]]
off, on, ratio = v[:n], v[n:2 * n], v[2 * n:]
print(f"{name:32s} {statistics.median(off):8.2f} {statistics.median(on):8.2f} "
      f"{statistics.median(ratio):8.3f}")
PY
done
