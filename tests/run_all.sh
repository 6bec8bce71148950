#!/usr/bin/env bash
# Runs every test of railcontact (the README's test command; CI runs it through .ci/run):
#   1. formatting and clippy with warnings as errors;
#   2. Rust unit and integration tests, then the continuity sweeps and random-walk soaks at full
#      resolution and the exact half-space comparisons in a release build;
#   3. packs the FMUs (release build; the Linux library against glibc 2.17 through cargo-zigbuild,
#      required here rather than used when found) and runs their default experiments through
#      the C API;
#   4. builds the Python package's wheel (python/, maturin: abi3, manylinux2014) into
#      target/wheels and installs it into the test venv;
#   5. the Python host tests (FMPy, libcosimpy, Ecos; the glibc baseline of the packed library;
#      fmu-pack --resource) against the packed FMUs, and the package's tests.
# Needs what .ci/setup installs (run `bash .ci/setup` first on a fresh machine).
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-.venv/bin/python}"

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test"
cargo test --workspace
echo "== continuity sweeps and random-walk soaks at full resolution (release)"
cargo test --release --test continuity --test soak
echo "== exact half-space comparisons in release (the rolling oracle's Newton systems)"
cargo test --release -p railcontact-halfspace --test halfspace_oracle --test wheel_forces --test frictional_power
echo "== fmu-pack (release build against glibc 2.17, pack, default experiments)"
cargo run --release -p fmu-pack -- --glibc 2.17
echo "== Python package (maturin: abi3 wheel against glibc 2.17, installed into the test venv)"
cargo fmt --manifest-path python/Cargo.toml -- --check
PATH="$PWD/.venv/bin:$PATH" cargo clippy --manifest-path python/Cargo.toml -- -D warnings
rm -rf target/wheels
PATH="$PWD/.venv/bin:$PATH" .venv/bin/maturin build --release -m python/Cargo.toml \
  --compatibility manylinux2014 --zig -o target/wheels
"$PYTHON" -m pip install -q --force-reinstall --no-deps target/wheels/railcontact-*.whl
echo "== Python host tests"
"$PYTHON" -m pytest tests/python -q
