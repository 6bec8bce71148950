#!/usr/bin/env bash
# The Python package's batch call against the FMU's C API, paired: for each configuration and
# round, the C host (benches/c_host/hunting.c: fmi2SetReal + fmi2DoStep per step, the packed
# FMU) and railcontact.solve_batch (one call, rows carried as steps, every Real output returned
# as NumPy arrays) run the same hunting motion of STEPS poses one after the other; prints the
# wall-clock µs per step and per row and their ratio per round, and the median ratio.
# Needs the packed FMU (`cargo run --release -p fmu-pack`) and the wheel installed in the venv
# (tests/run_all.sh builds and installs both).
# Usage: benches/python/batch.sh [STEPS] [ROUNDS]   (default 10 000 and 5)
set -euo pipefail
cd "$(dirname "$0")/../.."
STEPS="${1:-10000}"
ROUNDS="${2:-5}"
PYTHON="${PYTHON:-.venv/bin/python}"
# shellcheck source=benches/c_host/fmu_unpack.sh
. benches/c_host/fmu_unpack.sh normalModel tangentialModel planarPatch wearModel Qleft Qright y \
  yaw vx vy yawRate omega
gcc -O2 -std=c99 -o "$WORK/hunting" benches/c_host/hunting.c -ldl -lm
echo "$STEPS poses of the hunting motion: C API (µs/step) against railcontact.solve_batch (µs/row)"
printf "%-22s %6s %10s %10s %7s\n" configuration round "C API" Python ratio
for C in "Hertz+FASTSIM 1 1 0" "ANALYN+FASTSIM 6 1 0" "coupled+FaStrip,planar 7 3 1"; do
  read -r NAME N T P <<< "$C"
  RATIOS=()
  for R in $(seq "$ROUNDS"); do
    CAPI=$("$WORK/hunting" "$LIB" "$GUID" "$URI" hunting "$STEPS" "$N" "$T" "$P" 0 $VRS | cut -d' ' -f1)
    PY=$("$PYTHON" benches/python/batch.py "$STEPS" "$N" "$T" "$P")
    RATIO=$(python3 -c "print(f'{$PY / $CAPI:.3f}')")
    RATIOS+=("$RATIO")
    printf "%-22s %6s %10s %10s %7s\n" "$NAME" "$R" "$CAPI" "$PY" "$RATIO"
  done
  MEDIAN=$(printf "%s\n" "${RATIOS[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  printf "%-22s median ratio %s\n" "$NAME" "$MEDIAN"
done
