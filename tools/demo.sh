#!/usr/bin/env bash
# Builds a real OpenArena map from its .map source through all three stages with this compiler
# (-bsp -meta, -vis, -light -fast -sh) in a work folder outside the clone, then looks at the result.
# Usage: tools/demo.sh [build-dir] [map-name]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
map=${2:-oacmpdm1}
cache=$(tools/fetch-openarena.sh | tail -n 1)
q3map2="$PWD/$build/q3map2/q3map2"

work="$cache/demo/baseoa/maps"
mkdir -p "$work"
src=$(find "$cache/loose" -path "*/maps/$map.map" | head -n 1)
[ -n "$src" ] || { echo "demo: no .map source named $map in $cache" >&2; exit 1; }
rm -f "$work/$map".{bsp,prt,lin,srf}
cp "$src" "$work/$map.map"

game="-fs_basepath $cache/openarena -fs_game baseoa"
run() {
  echo "== $q3map2 $*"
  local start=$SECONDS
  "$q3map2" "$@"
  echo "   ($((SECONDS - start)) s)"
}
run $game -bsp -meta "$work/$map.map"
run $game -vis "$work/$map.bsp"
run $game -light -fast -sh "$work/$map.bsp"
run -shprobe "$work/$map.bsp" 0 0 64
run -info "$work/$map.bsp"
echo
echo "Compiled map: $work/$map.bsp (from $src)"
