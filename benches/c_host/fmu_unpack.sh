# Sourced by the C-host scripts of benches/c_host: unpacks the packed WheelRailContact FMU
# (`cargo run --release -p fmu-pack` first; FMU_DIR overrides target/fmu) into a temporary
# directory removed on exit, and sets WORK, LIB (its shared library), URI (its resources) and
# GUID, and VRS: the value references of the variables named in "$@", in that order.
FMU="${FMU_DIR:-target/fmu}/WheelRailContact.fmu"
[ -f "$FMU" ] || { echo "missing $FMU: run 'cargo run --release -p fmu-pack' first" >&2; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
python3 - "$FMU" "$WORK" "$@" > "$WORK/vars" <<'PY'
import sys, zipfile, xml.etree.ElementTree as ET
fmu, work, names = sys.argv[1], sys.argv[2], sys.argv[3:]
zipfile.ZipFile(fmu).extractall(work + "/fmu")
root = ET.parse(work + "/fmu/modelDescription.xml").getroot()
vr = {v.get("name"): v.get("valueReference") for v in root.iter("ScalarVariable")}
print(root.get("guid"), *(vr[n] for n in names))
PY
read -r GUID VRS < "$WORK/vars"
LIB="$WORK/fmu/binaries/linux64/WheelRailContact.so"
URI="file://$WORK/fmu/resources"
