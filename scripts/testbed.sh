#!/usr/bin/env bash
# Builds the browser testbed and serves it on localhost.
#
#   scripts/testbed.sh [--build-only] [--port N]
#
# Installs the wasm32-unknown-unknown target if missing, builds testbed/ for it
# (release: opt-level "s", LTO, panic = abort), copies the module to
# web/testbed.wasm and reports its size and the engine's alone (testbed/size-probe),
# writes web/native-hashes.json (the state hashes the native build computes for
# every scene), then serves web/ with python3's http.server at
# http://127.0.0.1:PORT/ (default 8000).
# Builds in $CARGO_TARGET_DIR (default: the repository's target/).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
BUILD_ONLY=0
PORT=8000
while [ $# -gt 0 ]; do
  case "$1" in
    --build-only) BUILD_ONLY=1 ;;
    --port) PORT="${2:?--port needs a number}"; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "testbed.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  echo "testbed: installing the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

cd "$ROOT/testbed"
echo "testbed: building the wasm module"
cargo build --release --lib --target wasm32-unknown-unknown
WASM="$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/arphysics_testbed.wasm"
cp "$WASM" "$ROOT/web/testbed.wasm"
RAW=$(wc -c < "$ROOT/web/testbed.wasm")
GZ=$(gzip -9 -c "$ROOT/web/testbed.wasm" | wc -c)
echo "testbed: web/testbed.wasm is $((RAW / 1024)) KB ($((GZ / 1024)) KB gzipped)"
# The engine's own share: testbed/size-probe uses every feature once and
# nothing else, built with the same profile (issue 20's aim: under 300 KB).
(cd "$ROOT/testbed/size-probe" && cargo build --quiet --release --target wasm32-unknown-unknown)
PROBE="$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/arphysics_size_probe.wasm"
ERAW=$(wc -c < "$PROBE")
EGZ=$(gzip -9 -c "$PROBE" | wc -c)
echo "testbed: the engine alone (testbed/size-probe, every feature used once) is $((ERAW / 1024)) KB ($((EGZ / 1024)) KB gzipped; aim: under 300 KB)"

echo "testbed: computing the native hashes"
# The native side at opt-level 3 (faster; the bits are the same at every level).
CARGO_PROFILE_RELEASE_OPT_LEVEL=3 cargo run --quiet --release --bin native_hashes -- --out "$ROOT/web/native-hashes.json"

if [ "$BUILD_ONLY" = 1 ]; then
  exit 0
fi
echo "testbed: serving web/ at http://127.0.0.1:$PORT/ (Ctrl-C stops)"
exec python3 -m http.server "$PORT" --bind 127.0.0.1 --directory "$ROOT/web"
