#!/usr/bin/env bash
# Runs the compiler on a real OpenArena map in a work folder outside the clone.
# Usage: tools/demo.sh [build-dir] [map-name]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
map=${2:-oacmpdm1}
cache=$(tools/fetch-openarena.sh | tail -n 1)
q3map2="$PWD/$build/q3map2/q3map2"

work="$cache/demo/baseoa/maps"
mkdir -p "$work"
bsp=$(find "$cache/loose" -path "*/maps/$map.bsp" | head -n 1)
src=$(find "$cache/loose" -path "*/maps/$map.map" | head -n 1)
[ -n "$bsp" ] || { echo "demo: no map named $map in $cache" >&2; exit 1; }
cp "$bsp" "$work/$map.bsp"
[ -z "$src" ] || cp "$src" "$work/$map.map"

game="-fs_basepath $cache/openarena -fs_game baseoa"
echo "== $q3map2 $game -light -fast -sh $work/$map.bsp"
"$q3map2" $game -light -fast -sh "$work/$map.bsp"
echo "== $q3map2 -shprobe $work/$map.bsp 0 0 64"
"$q3map2" -shprobe "$work/$map.bsp" 0 0 64
echo "== $q3map2 -info $work/$map.bsp"
"$q3map2" -info "$work/$map.bsp"
echo
echo "Relit map: $work/$map.bsp"
