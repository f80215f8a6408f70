#!/usr/bin/env bash
# Fetches OpenArena's Debian packages (real q3map2-compiled maps, .map sources, shaders, textures)
# into a cache folder outside the clone and unpacks them. A no-op when the cache is complete.
# Prints the cache root on the last line. Exit status is non-zero when the data cannot be had.
#   cache root: $Q3MAP_DATA_CACHE, else $XDG_CACHE_HOME/q3map2-data, else ~/.cache/q3map2-data
set -euo pipefail

packages=(openarena-oacmp1 openarena-081-maps openarena-081-textures openarena-085-data openarena-088-data
          openarena-data openarena-081-misc)
cache="${Q3MAP_DATA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/q3map2-data}"
stamp="$cache/.complete-v2"

if [ -f "$stamp" ]; then
  echo "$cache"
  exit 0
fi

command -v unzip >/dev/null || { echo "fetch-openarena: 'unzip' is missing (tools/install-deps.sh test)" >&2; exit 1; }
mkdir -p "$cache/debs" "$cache/root"

need_update=1
for p in "${packages[@]}"; do
  if ! ls "$cache/debs/${p}"_*.deb >/dev/null 2>&1; then
    if [ $need_update -eq 1 ]; then
      if [ "$(id -u)" -eq 0 ]; then apt-get update -qq; else sudo apt-get update -qq; fi
      need_update=0
    fi
    (cd "$cache/debs" && apt-get download -qq "$p") || {
      echo "fetch-openarena: cannot download Debian package '$p'" >&2; exit 1; }
  fi
done

for deb in "$cache"/debs/*.deb; do
  dpkg-deb -x "$deb" "$cache/root"
done

# The game tree (basepath with baseoa/ and oacmp-mod/) is linked as "openarena". The small,
# often-used files (maps, .map sources, shader scripts) are also unpacked per pk3 under loose/ so
# tests can open them as plain files; textures stay inside the pk3s.
ln -sfn "$cache/root/usr/share/games/openarena" "$cache/openarena"
rm -rf "$cache/loose"
mkdir -p "$cache/loose"
find "$cache/openarena/" -name '*.pk3' -print0 | sort -z | while IFS= read -r -d '' pk3; do
  unzip -qq -o -C "$pk3" 'maps/*.bsp' 'sources/maps/*.map' 'maps/*.map' 'scripts/*.shader' \
    'scripts/*.txt' -d "$cache/loose/$(basename "$pk3" .pk3)" 2>/dev/null || true
done

nbsp=$(find "$cache/loose" -iname '*.bsp' | wc -l)
nmap=$(find "$cache/loose" -iname '*.map' | wc -l)
if [ "$nbsp" -lt 50 ] || [ "$nmap" -lt 13 ]; then
  echo "fetch-openarena: unpacked only $nbsp BSPs and $nmap .map sources from $cache; expected more" >&2
  exit 1
fi
touch "$stamp"
echo "$cache"
