# The two set-up commands of the README:
#   make demo   install the Debian packages the demo needs, build cbtlc and cbtl only, run the main job
#   make test   install every package the tests need, build everything, then every test through ctest
BUILD_DIR  ?= build
BUILD_TYPE ?= RelWithDebInfo
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

.PHONY: all deps deps-demo configure build demo test asan fuzz fuzz-runtime bench golden-update format clean

all: build

deps:
	@scripts/install-deps.sh

deps-demo:
	@scripts/install-deps.sh --demo

$(BUILD_DIR)/build.ninja: | deps
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS)

# A build folder `make demo` configured without tests and benchmarks gets them back here.
configure: deps $(BUILD_DIR)/build.ninja
	@if grep -q '^CBTL_BUILD_TESTS:BOOL=OFF' $(BUILD_DIR)/CMakeCache.txt; then \
	  cmake -S . -B $(BUILD_DIR) -DCBTL_BUILD_TESTS=ON -DCBTL_BUILD_BENCH=ON; fi

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The demo needs two executables, not the tests and benchmarks (a third of the compilation), nor SLURM, Chromium,
# Node.js or the test frameworks.
demo: deps-demo
	@scripts/demo.sh --announce
	@test -f $(BUILD_DIR)/build.ninja || cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) \
	  -DCBTL_BUILD_TESTS=OFF -DCBTL_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build $(BUILD_DIR) -j $(JOBS) --target cbtlc cbtl
	@scripts/demo.sh $(BUILD_DIR)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# Every test again under AddressSanitizer and UndefinedBehaviorSanitizer, in build-asan/. tests/lsan.supp lists the
# third-party libraries' process-lifetime caches LeakSanitizer must not count (fontconfig's).
asan:
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	  $(MAKE) test BUILD_DIR=build-asan BUILD_TYPE=Debug CMAKE_ARGS="-DCBTL_SANITIZE=ON -DCBTL_BUILD_BENCH=OFF -DCBTL_PRECOMPILED_HEADERS=OFF"

# The compiler fuzzer for FUZZ_SECONDS (default 60), built with clang in build-fuzz/.
FUZZ_SECONDS ?= 60
fuzz: deps
	scripts/fuzz.sh $(FUZZ_SECONDS) cbtlc

# The runtime fuzzer (load, solve, re-check, unroll, learn) for FUZZ_SECONDS, in the same build-fuzz/.
fuzz-runtime: deps
	scripts/fuzz.sh $(FUZZ_SECONDS) runtime

bench: build
	scripts/bench.sh $(BUILD_DIR)

# Rewrites the golden .out/.err files from the current compiler; review the diff before committing.
golden-update: build
	CBTL_UPDATE_GOLDEN=1 ctest --test-dir $(BUILD_DIR) -L golden -j $(JOBS)

# Applies .clang-format to every C++ file (the test format.clang_format checks it).
format:
	scripts/check-format.sh --fix

clean:
	rm -rf $(BUILD_DIR)
