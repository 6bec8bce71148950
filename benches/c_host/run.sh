#!/usr/bin/env bash
# Times fmi2DoStep of the packed WheelRailContact FMU from a C host:
# 10 000 steps at the 78.5 kN central case for Hertz + FASTSIM and STRIPES A&B + FASTSIM (and
# ANALYN), with constant inputs and with a moving wheelset (y = 3 mm sin 2πt at 1 ms steps).
# Needs the packed FMU: `cargo run --release -p fmu-pack` first. Usage: benches/c_host/run.sh [STEPS]
set -euo pipefail
cd "$(dirname "$0")/../.."
STEPS="${1:-10000}"
FMU="${FMU_DIR:-target/fmu}/WheelRailContact.fmu"
[ -f "$FMU" ] || { echo "missing $FMU: run 'cargo run --release -p fmu-pack' first" >&2; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
python3 - "$FMU" "$WORK" > "$WORK/vars" <<'PY'
import sys, zipfile, xml.etree.ElementTree as ET
fmu, work = sys.argv[1], sys.argv[2]
zipfile.ZipFile(fmu).extractall(work + "/fmu")
root = ET.parse(work + "/fmu/modelDescription.xml").getroot()
vr = {v.get("name"): v.get("valueReference") for v in root.iter("ScalarVariable")}
print(root.get("guid"), vr["normalModel"], vr["Qleft"], vr["Qright"], vr["y"])
PY
read -r GUID VR_MODEL VR_QL VR_QR VR_Y < "$WORK/vars"
gcc -O2 -std=c99 -o "$WORK/dostep" benches/c_host/dostep.c -ldl -lm
LIB="$WORK/fmu/binaries/linux64/WheelRailContact.so"
URI="file://$WORK/fmu/resources"
echo "fmi2DoStep from a C host, $STEPS steps, mean µs per step (machine: $(nproc) cores)"
printf "%-28s %10s %10s\n" "normalModel" "constant" "moving"
declare -A T
for M in 1 5 6; do
  NAME=$([ $M = 1 ] && echo "1 Hertz + FASTSIM" || ([ $M = 5 ] && echo "5 STRIPES A&B + FASTSIM" || echo "6 ANALYN + FASTSIM"))
  C=$("$WORK/dostep" "$LIB" "$GUID" "$URI" "$VR_MODEL" "$M" "$VR_QL" "$VR_QR" "$VR_Y" "$STEPS" 0)
  MV=$("$WORK/dostep" "$LIB" "$GUID" "$URI" "$VR_MODEL" "$M" "$VR_QL" "$VR_QR" "$VR_Y" "$STEPS" 1)
  T[$M,0]=$C; T[$M,1]=$MV
  printf "%-28s %10s %10s\n" "$NAME" "$C" "$MV"
done
python3 -c "import sys; a=[float(x) for x in sys.argv[1:]]; print(f'ratio STRIPES A&B / Hertz: constant {a[1]/a[0]:.2f}, moving {a[3]/a[2]:.2f}')" \
  "${T[1,0]}" "${T[5,0]}" "${T[1,1]}" "${T[5,1]}"
