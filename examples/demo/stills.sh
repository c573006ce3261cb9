#!/usr/bin/env bash
# Renders stills of a demo SVG at given times with headless Chromium, to check
# the animation and to make the README's PNGs. Not part of CI.
#
#   examples/demo/stills.sh docs/demo-default.svg OUT_PREFIX 0.5 3 6
#
# writes OUT_PREFIX-0.5.png, OUT_PREFIX-3.png, … Each still is taken from an HTML
# page that inlines the SVG, pauses its SMIL animations and seeks to the time.
# Needs `chromium` (Debian: apt-get install chromium).
set -euo pipefail
svg=$1
prefix=$2
shift 2
size=$(sed -n 's/^<svg [^>]*width="\([0-9]*\)" height="\([0-9]*\)".*/\1,\2/p' "$svg" | head -1)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for t in "$@"; do
  page="$tmp/still-$t.html"
  {
    echo '<!doctype html><html><body style="margin:0">'
    cat "$svg"
    echo "<script>const s = document.querySelector('svg'); s.pauseAnimations(); s.setCurrentTime($t);</script>"
    echo '</body></html>'
  } >"$page"
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
    --disable-background-networking --disable-component-update --disable-sync \
    --no-first-run --user-data-dir="$tmp/profile" \
    --screenshot="$prefix-$t.png" --window-size="$size" "file://$page" 2>/dev/null
  echo "$prefix-$t.png"
done
