#!/usr/bin/env bash
# Compiles every oacmp map with this build's stages (-bsp -meta, -vis -fast, then -light -fast with
# and without -sh -shbspx) and has the patched ioquake3 renderer load each result strictly
# (q3-screenshot -s: any renderer warning about the BSP fails) in a third-person shot. Prints one
# line per map and file; exit 1 when any load failed or a lump was not used as expected.
#
# Usage: tools/engine/ioq3-sh/load-all.sh [WORKDIR] [MAP...]
#   WORKDIR defaults to build/ioq3-sh-load; the maps to all 13 .map sources of the data cache.
#   Q3MAP2 (default build/q3map2/q3map2), Q3_ENGINE_TOOLS, Q3_ENGINE_DATA as for the tests.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
project=$(cd "$here/../../.." && pwd)
work=${1:-$project/build/ioq3-sh-load}
shift || true
cache=${Q3MAP_DATA_CACHE:-$HOME/.cache/q3map2-data}
sources=$cache/loose/z_oacmp-volume1-v3/sources/maps
q3map2=${Q3MAP2:-$project/build/q3map2/q3map2}
tools=${Q3_ENGINE_TOOLS:-$project/../shared/tools}
[[ -x $tools/q3-screenshot ]] || tools=/work/shared/tools
data=${Q3_ENGINE_DATA:-/usr/share/games/openarena}
oacmp=$cache/openarena/baseoa/z_oacmp-volume1-v3.pk3

client=$("$here/build.sh" | tail -n 1)/ioquake3
maps=("$@")
if ((${#maps[@]} == 0)); then
  for f in "$sources"/*.map; do maps+=("$(basename "$f" .map)"); done
fi

stage() { (cd "$work/$1/baseoa" && nice "$q3map2" -fs_basepath "$cache/openarena" -fs_game baseoa "${@:2}") >>"$work/$1.log" 2>&1; }

failed=0
for name in "${maps[@]}"; do
  mkdir -p "$work/$name/baseoa/maps"
  : >"$work/$name.log"
  cp "$sources/$name.map" "$work/$name/baseoa/maps/"
  t0=$(date +%s)
  stage "$name" -bsp -meta "maps/$name.map"
  stage "$name" -vis -fast "maps/$name.bsp"
  cp "$work/$name/baseoa/maps/$name.bsp" "$work/$name/${name}_vis.bsp"
  for variant in plain sh; do
    cp "$work/$name/${name}_vis.bsp" "$work/$name/baseoa/maps/$name.bsp"
    if [[ $variant == sh ]]; then stage "$name" -light -fast -sh -shbspx "maps/$name.bsp"
    else stage "$name" -light -fast "maps/$name.bsp"; fi
    file=$work/$name/${name}_$variant.bsp
    cp "$work/$name/baseoa/maps/$name.bsp" "$file"
    logs=$work/$name/logs-$variant
    status=0
    IOQ3=$client nice "$tools/q3-screenshot" -s -e ioq3 -m third -S 640x480 -b "$data" -p "$oacmp" \
      -o "$work/$name/$variant" -l "$logs" "$file" >"$work/$name/$variant.out" 2>&1 || status=$?
    log=$logs/${name}_$variant.ioq3-client.log
    loaded=$(grep -ac '^SH light grid:' "$log" || true)
    warned=$(grep -aci 'WARNING' "$log" || true)
    expect=$([[ $variant == sh ]] && echo 1 || echo 0)
    verdict=OK
    if ((status != 0 || loaded != expect)) || grep -aq 'LIGHTGRID_SH' "$log"; then verdict=FAIL; failed=1; fi
    printf '%-10s %-5s %-4s  strict exit %d, SH grid loaded %d, warnings %d, %ds\n' \
      "$name" "$variant" "$verdict" "$status" "$loaded" "$warned" $(($(date +%s) - t0))
  done
done
exit "$failed"
