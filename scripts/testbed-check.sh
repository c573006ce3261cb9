#!/usr/bin/env bash
# The testbed tested in a real browser: headless Chromium loads
# web/index.html?check=1, which runs every scene its check frame count without
# animation, compares each state hash with the native build's
# (web/native-hashes.json), rolls each back and re-simulates, exercises the
# bad-input paths (unknown scene, spawn outside the bounds, drag on a static
# body, a full world, a trap) and writes the results into the page. This script
# reads them with --dump-dom, fails on any mismatch, trap or console message,
# and saves a screenshot of the default scene.
#
#   scripts/testbed-check.sh
#
# Installs Debian's chromium if missing, builds with scripts/testbed.sh
# --build-only, serves web/ on a free localhost port. Needs no display; works
# as root (--no-sandbox). Results in $CARGO_TARGET_DIR/testbed/ (default
# target/testbed/): check.txt, dom.html, chromium.log, testbed.png.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
OUT="$CARGO_TARGET_DIR/testbed"
START=$(date +%s)

missing=()
command -v chromium >/dev/null 2>&1 || missing+=(chromium)
command -v python3 >/dev/null 2>&1 || missing+=(python3)
if [ "${#missing[@]}" -gt 0 ]; then
  echo "testbed-check: installing ${missing[*]}"
  SUDO=()
  [ "$(id -u)" -eq 0 ] || SUDO=(sudo)
  "${SUDO[@]}" apt-get update -qq || true
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y -qq "${missing[@]}"
fi

"$ROOT/scripts/testbed.sh" --build-only
BUILT=$(date +%s)

rm -rf "$OUT"
mkdir -p "$OUT"
PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$PORT" --bind 127.0.0.1 --directory "$ROOT/web" > "$OUT/server.log" 2>&1 &
SERVER=$!
cleanup() { kill "$SERVER" 2>/dev/null || true; }
trap cleanup EXIT
URL="http://127.0.0.1:$PORT/index.html"
# Wait (at most 10 s) for the server.
python3 - "$URL" <<'PY'
import sys, time, urllib.request
for _ in range(100):
    try:
        urllib.request.urlopen(sys.argv[1], timeout=1).read()
        sys.exit(0)
    except Exception:
        time.sleep(0.1)
sys.exit("testbed-check: the local server did not start")
PY

FLAGS=(--headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run
  --no-default-browser-check --disable-extensions --enable-logging=stderr --v=0
  --user-data-dir="$OUT/profile")

# The check: virtual time runs the page's timers without waiting; the dump
# happens once the page is idle (or the budget is spent).
# Like the screenshot below, the dump may come before the module has loaded
# (nothing in #check yet): then it runs again, at most 3 times.
for attempt in 1 2 3; do
  set +e
  timeout -k 10 300 chromium "${FLAGS[@]}" --virtual-time-budget=600000 \
    --dump-dom "$URL?check=1" > "$OUT/dom.html" 2> "$OUT/chromium.log"
  RC=$?
  set -e
  if [ "$RC" -ne 0 ]; then
    echo "testbed-check: chromium exited with $RC (124: timed out); see $OUT/chromium.log" >&2
    exit 1
  fi
  grep -q '<div id="check"></div>' "$OUT/dom.html" || break
  echo "testbed-check: attempt $attempt dumped the page before the check started; again"
done
CHECKED=$(date +%s)

# The screenshot: the default scene after 240 frames. Headless Chromium now and
# then shoots before the module has loaded; the DOM dumped in the same run
# tells (the frame counter reads 240 once it has), and then it tries again,
# with more virtual time each attempt (3 s once failed three times in a row on a
# fresh clone: the page had not loaded the module yet).
SHOT=1
for attempt in 1 2 3 4 5; do
  BUDGET=$((attempt * 5000))
  rm -f "$OUT/testbed.png"
  set +e
  timeout -k 10 120 chromium "${FLAGS[@]}" --window-size=1400,760 --hide-scrollbars \
    --virtual-time-budget="$BUDGET" --dump-dom --screenshot="$OUT/testbed.png" "$URL?scene=default&frames=240" \
    2> "$OUT/chromium-screenshot.log" > "$OUT/screenshot-dom.html"
  RC=$?
  set -e
  if [ "$RC" -eq 0 ] && grep -q 'id="frame">240<' "$OUT/screenshot-dom.html"; then
    SHOT=0
    break
  fi
  echo "testbed-check: screenshot attempt $attempt caught the page before it loaded; again"
done

python3 - "$OUT" "$SHOT" <<'PY'
import html, os, re, sys
out, shot = sys.argv[1], int(sys.argv[2])
dom = open(os.path.join(out, "dom.html"), encoding="utf-8").read()
fails = []
m = re.search(r'<div id="check">(.*?)</div>', dom, re.S)
lines = html.unescape(m.group(1)).splitlines() if m else []
open(os.path.join(out, "check.txt"), "w", encoding="utf-8").write("\n".join(lines) + "\n")
for l in lines:
    print("  " + l)
if not lines:
    fails.append("the page wrote no results (did testbed.wasm load?)")
fails += [l for l in lines if not l.startswith("ok ")]
status = re.search(r'<div id="check-status">(.*?)</div>', dom)
if not status:
    fails.append("the page did not finish the check (no #check-status)")
elif status.group(1) != "PASS":
    fails.append("page status: " + status.group(1))
if 'id="trap" style="display: block' in dom:
    fails.append("the page shows a trap")
for name in ("chromium.log", "chromium-screenshot.log"):
    for l in open(os.path.join(out, name), encoding="utf-8", errors="replace"):
        if ":CONSOLE" in l:
            fails.append("console (%s): %s" % (name, l.strip()))
png = os.path.join(out, "testbed.png")
if shot != 0 or not os.path.exists(png) or os.path.getsize(png) < 1000:
    fails.append("no screenshot of the loaded page in 5 attempts")
else:
    print("  screenshot: %s (%d KB)" % (png, os.path.getsize(png) // 1024))
if fails:
    print("testbed-check: FAILED")
    for f in fails:
        print("  " + f)
    sys.exit(1)
print("testbed-check: every scene has the same bits as native")
PY
END=$(date +%s)
echo "testbed-check: passed in $((END - START)) s (build $((BUILT - START)) s, browser check $((CHECKED - BUILT)) s, screenshot $((END - CHECKED)) s)"
