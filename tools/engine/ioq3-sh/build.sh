#!/usr/bin/env bash
# Builds ioquake3's renderers with the SH light grid patch and prints the folder that holds them
# beside a copy of Debian's ioquake3 client (point the engine scripts' IOQ3 at DIR/ioquake3).
#
# Usage: tools/engine/ioq3-sh/build.sh
#   $IOQ3_SOURCE   ioquake3 source tarball (default: ../shared/third_party/ioq3-70d07d91-src.tar.xz
#                  beside the project, else /work/shared/third_party)
#   $IOQ3_SH_CACHE cache root (default: ${Q3MAP_DATA_CACHE:-~/.cache/q3map2-data}/ioq3-sh)
#
# The build lands in CACHE/<hash of the patch, this script and the tarball>, so it runs once per
# patch (about a minute on 2 cores) and later calls only print the folder. Exit status: 0 built or
# cached, 1 the build failed, 3 something it needs is missing (named on stderr).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
project=$(cd "$here/../../.." && pwd)
patch_file=$here/renderergl1-sh-grid.patch

missing() { echo "ioq3-sh: $*" >&2; exit 3; }

source_tar=${IOQ3_SOURCE:-}
if [[ -z $source_tar ]]; then
  for candidate in "$project/../shared/third_party/ioq3-70d07d91-src.tar.xz" \
                   /work/shared/third_party/ioq3-70d07d91-src.tar.xz; do
    [[ -f $candidate ]] && { source_tar=$candidate; break; }
  done
fi
[[ -n $source_tar && -f $source_tar ]] || missing "no ioquake3 source tarball (set IOQ3_SOURCE)"
client=/usr/lib/ioquake3/ioquake3
[[ -x $client ]] || missing "no $client (Debian package ioquake3)"
for header in /usr/include/SDL2/SDL.h /usr/include/jpeglib.h; do
  [[ -f $header ]] || missing "no $header (Debian packages libsdl2-dev libjpeg-dev)"
done
for tool in make cc patch xz sha256sum flock; do
  command -v "$tool" >/dev/null || missing "no $tool on PATH"
done

key=$(cat "$patch_file" "${BASH_SOURCE[0]}" "$source_tar" | sha256sum | cut -c1-16)
cache_root=${IOQ3_SH_CACHE:-${Q3MAP_DATA_CACHE:-$HOME/.cache/q3map2-data}/ioq3-sh}
out=$cache_root/$key
mkdir -p "$cache_root"

# Parallel test processes may ask at once: one builds, the others wait for it.
exec 9>"$cache_root/.lock"
flock 9
if [[ -x $out/ioquake3 && -f $out/renderer_opengl1_x86_64.so ]]; then
  echo "$out"
  exit 0
fi

work=$(mktemp -d "$cache_root/build.XXXXXX")
trap 'rm -rf "$work"' EXIT
tar -xJf "$source_tar" -C "$work"
src=$(find "$work" -mindepth 1 -maxdepth 1 -type d | head -n 1)
patch -d "$src" -p1 --quiet <"$patch_file"
if ! nice make -C "$src" -j2 release BUILD_SERVER=0 BUILD_GAME_SO=0 BUILD_GAME_QVM=0 BUILD_BASEGAME=0 \
    BUILD_MISSIONPACK=0 BUILD_AUTOUPDATER=0 USE_CURL=0 USE_OPENAL=0 USE_CODEC_VORBIS=0 \
    USE_CODEC_OPUS=0 USE_VOIP=0 USE_INTERNAL_LIBS=0 USE_RENDERER_DLOPEN=1 >"$work/build.log" 2>&1; then
  tail -n 30 "$work/build.log" >&2
  echo "ioq3-sh: the renderer build failed" >&2
  exit 1
fi
staging=$out.tmp
rm -rf "$staging"
mkdir -p "$staging"
cp "$src"/build/release-*/renderer_opengl1_*.so "$src"/build/release-*/renderer_opengl2_*.so "$staging/"
# Debian's client carries the patches OpenArena's native game modules need; it loads the renderer
# from its own folder.
cp "$client" "$staging/ioquake3"
rm -rf "$out"
mv "$staging" "$out"
echo "$out"
