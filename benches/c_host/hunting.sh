#!/usr/bin/env bash
# Steps the packed WheelRailContact FMU from a C host (benches/c_host/hunting.c) through a
# hunting motion — y = 3 mm sin 2π·5 Hz·t, yaw = 1 mrad sin 2π·5 Hz·t, consistent vy and yaw
# rate, built-in S1002/UIC60, 78.5 kN per wheel, kinematic creepages at 30 m/s, 1 ms steps — and
# through the steady central case, for the configurations of docs/performance.md. Prints per
# configuration the wall clock's mean, median, 99th percentile and largest step [µs] (each step
# timed), the thread CPU time's median and 99th percentile (without preemptions by other
# processes), and the ratios of the wall-clock means and of the CPU medians to Hertz + FASTSIM's
# in the same run.
# Needs the packed FMU: `cargo run --release -p fmu-pack` first.
# Usage: benches/c_host/hunting.sh [STEPS]   (default 20 000)
set -euo pipefail
cd "$(dirname "$0")/../.."
STEPS="${1:-20000}"
# shellcheck source=benches/c_host/fmu_unpack.sh
. benches/c_host/fmu_unpack.sh normalModel tangentialModel planarPatch wearModel Qleft Qright y \
  yaw vx vy yawRate omega
gcc -O2 -std=c99 -o "$WORK/hunting" benches/c_host/hunting.c -ldl -lm
run() { "$WORK/hunting" "$LIB" "$GUID" "$URI" "$1" "$STEPS" "$2" "$3" "$4" "${5:-0}" $VRS; }
echo "fmi2DoStep from a C host, $STEPS steps of 1 ms, µs per step (machine: $(nproc) cores, $(uname -m))"
printf "%-26s %-8s %8s %8s %8s %8s %8s %8s %6s %6s\n" configuration motion mean median p99 max \
  cpu-med cpu-p99 ratio cpu-r
# name normalModel tangentialModel planarPatch
CONFIGS=(
  "Hertz+FASTSIM 1 1 0"
  "ANALYN+FASTSIM,planar 6 1 1"
  "ANALYN+FaStrip,planar 6 3 1"
  "Kik-Piotrowski+FASTSIM 3 1 0"
  "Linder+FASTSIM 2 1 0"
  "STRIPES-B+FASTSIM 4 1 0"
  "STRIPES-A&B+FASTSIM 5 1 0"
  "ANALYN+FASTSIM 6 1 0"
  "ANALYN+FaStrip 6 3 0"
  "coupled+FASTSIM 7 1 0"
  "coupled+FaStrip,planar 7 3 1"
  "ANALYN+FaStrip-coupled,planar 6 5 1"
  "coupled+FaStrip-coupled,planar 7 5 1"
)
declare -A BASE BASE_CPU
for MOTION in hunting steady; do
  for C in "${CONFIGS[@]}"; do
    read -r NAME N T P <<< "$C"
    read -r MEAN MEDIAN P99 MAX CPU_MEDIAN CPU_P99 <<< "$(run "$MOTION" "$N" "$T" "$P")"
    [ -n "${BASE[$MOTION]:-}" ] || { BASE[$MOTION]=$MEAN; BASE_CPU[$MOTION]=$CPU_MEDIAN; }
    RATIO=$(python3 -c "print(f'{$MEAN / ${BASE[$MOTION]}:.2f}')")
    CPU_RATIO=$(python3 -c "print(f'{$CPU_MEDIAN / ${BASE_CPU[$MOTION]}:.2f}')")
    printf "%-26s %-8s %8s %8s %8s %8s %8s %8s %6s %6s\n" "$NAME" "$MOTION" "$MEAN" "$MEDIAN" \
      "$P99" "$MAX" "$CPU_MEDIAN" "$CPU_P99" "$RATIO" "$CPU_RATIO"
  done
done
