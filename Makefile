# Thin wrapper over CMake. `make demo` and `make test` do all set-up on a fresh Debian 12 machine.
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
export CCACHE_BASEDIR := $(CURDIR)

.PHONY: all deps data build demo test test-fast test-asan clean

all: build

deps:
	tools/install-deps.sh build test engines

data: deps
	tools/fetch-openarena.sh

build: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

demo: build data
	tools/demo.sh $(BUILD)

# The whole suite: release build, then the same tests under AddressSanitizer + UBSan.
test: data
	tools/run-tests.sh $(BUILD) $(ASAN_BUILD)

# Release build only (quicker while developing).
test-fast: build data
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
