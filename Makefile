# lumaslam front door. `make demo` and `make test` set up a fresh Debian 12 machine first.
MAKEFLAGS += --no-print-directory
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
SHARED ?= $(abspath ../shared)
CMAKE_FLAGS ?=

.PHONY: all deps configure build demo test test-strength test-tsan test-asan fuzz bench bench-dynamic clean format

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DLUMASLAM_SHARED_DIR=$(SHARED) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The demo needs only the CLI: a fresh machine reaches its output without building the tests.
# With the shared YOLO model it adds a row with YOLO in the loop (else it says how to get one).
DEMO_MODEL ?= $(SHARED)/models/yolov5n-320.onnx
demo: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target lumaslam_cli
	$(BUILD_DIR)/lumaslam demo --out $(BUILD_DIR)/demo$(if $(wildcard $(DEMO_MODEL)), --model $(DEMO_MODEL))

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# Mutation check (issue 22, docs/testing.md): breaks one thing at a time in a worktree of HEAD
# and lists the accuracy tests that fail; fails if a mutation is not caught. ~45 min.
test-strength: deps
	@SHARED=$(SHARED) JOBS=$(JOBS) CMAKE_FLAGS="$(CMAKE_FLAGS)" scripts/test-strength.sh

# Sanitizer suites (not part of `make test`; each builds its own tree, much slower than
# Release). SANITIZER_TESTS narrows them to executables (a ctest -L label regex), e.g.
# SANITIZER_TESTS='test_system|test_loop_closer'.
# TSan runs OpenCV, TBB (src/lumaslam/core/serial_libraries.h) and OpenMP (OMP_THREAD_LIMIT)
# single-threaded, so its reports are races between our own threads; tests/*.supp list the
# third-party exceptions.
SANITIZER_TESTS ?= .
SANITIZER_CMAKE = -DCMAKE_BUILD_TYPE=Release -DLUMASLAM_SHARED_DIR=$(SHARED) \
	-DLUMASLAM_BUILD_BENCH=OFF -DCMAKE_OPTIMIZE_DEPENDENCIES=ON $(CMAKE_FLAGS)

test-tsan: deps
	@cmake -S . -B build-tsan -DLUMASLAM_SANITIZE=thread $(SANITIZER_CMAKE) >/dev/null
	@cmake --build build-tsan -j $(JOBS)
	@cd build-tsan && OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 TSAN_OPTIONS="suppressions=$(CURDIR)/tests/tsan.supp second_deadlock_stack=1" \
		ctest --output-on-failure -j $(JOBS) -L '$(SANITIZER_TESTS)'

# OPENCV_VIDEOIO_PRIORITY_GPHOTO2=0: OpenCV probes libgphoto2 for any video file it cannot
# open, and libgphoto2 leaks its USB device list (and allocations of camera drivers it unloads,
# which LeakSanitizer cannot name for a suppression).
test-asan: deps
	@cmake -S . -B build-asan -DLUMASLAM_SANITIZE=address,undefined $(SANITIZER_CMAKE) >/dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ASAN_OPTIONS=check_initialization_order=1 OPENCV_VIDEOIO_PRIORITY_GPHOTO2=0 \
		LSAN_OPTIONS="suppressions=$(CURDIR)/tests/lsan.supp" \
		UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --output-on-failure -j $(JOBS) -L '$(SANITIZER_TESTS)'

# libFuzzer targets of fuzz/ (docs/testing.md, "Fuzzing"): a clang build of only the parsers
# with ASan and UBSan, each target run FUZZ_SECONDS on its seeds; fails on any finding.
# FUZZ_TARGETS narrows the run, e.g. FUZZ_TARGETS='map_file vocabulary'.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= settings trajectory tum_index kitti_calib kitti_poses euroc_sensor \
	euroc_index folder_timestamps box_file class_names box_labels map_file vocabulary \
	experiment_plan
fuzz:
	@scripts/install-deps.sh --fuzz
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DLUMASLAM_FUZZ=ON \
		-DLUMASLAM_SANITIZE=fuzzer-no-link,address,undefined -DLUMASLAM_BUILD_TESTS=OFF \
		-DLUMASLAM_BUILD_PYTHON=OFF $(SANITIZER_CMAKE) >/dev/null
	@cmake --build build-fuzz -j $(JOBS) --target fuzz_seeds $(addprefix fuzz_,$(FUZZ_TARGETS))
	@scripts/run-fuzzers.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

bench: build
	$(BUILD_DIR)/lumaslam_bench --benchmark_min_time=0.2

# Dynamic-scene table of docs/dynamic.md (issue 16): every walking sequence x removal
# configuration x 5 seeds, threaded mapping; BENCH_DYNAMIC_ARGS narrows it (see the script).
bench-dynamic: build
	scripts/bench-dynamic.py --lumaslam $(BUILD_DIR)/lumaslam --shared $(SHARED) $(BENCH_DYNAMIC_ARGS)

format:
	@find src apps tests bench -name '*.h' -o -name '*.cpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
