#!/usr/bin/env bash
# Installs the Debian packages the build and the tests need; a no-op when all are present.
# Usage: tools/install-deps.sh [build|test|engines]...   (default: build test)
set -euo pipefail

build_pkgs=(cmake ninja-build g++ pkg-config libembree-dev libtbb-dev libjpeg62-turbo-dev libpng-dev
            zlib1g-dev libminizip-dev rapidjson-dev libxml2-dev libglib2.0-dev libgtest-dev libassimp-dev
            libjemalloc-dev libbenchmark-dev ccache)
# The reference q3map2's runtime libraries too: its wrapper installs them when missing, but tests run
# it from parallel processes, and on a fresh machine all but one of them lost the race for apt's lock.
test_pkgs=(clang libclang-rt-14-dev glslang-tools unzip ca-certificates python3 time
           libassimp5 libdraco7 libglib2.0-0 libjpeg62-turbo libminizip1 libpng16-16 libxml2)
# libsdl2-dev: the headers the patched ioquake3 renderer (tools/engine/ioq3-sh) builds against.
engine_pkgs=(ioquake3 ioquake3-server openarena openarena-server darkplaces darkplaces-server
             fteqcc xvfb xauth libgl1-mesa-dri imagemagick libsdl2-dev)

groups=("$@")
[ ${#groups[@]} -gt 0 ] || groups=(build test)

want=()
for g in "${groups[@]}"; do
  case "$g" in
    build) want+=("${build_pkgs[@]}") ;;
    test) want+=("${test_pkgs[@]}") ;;
    engines) want+=("${engine_pkgs[@]}") ;;
    *) echo "install-deps: unknown group '$g' (expected build, test or engines)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${want[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
