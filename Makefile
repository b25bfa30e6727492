# softshadow: the two set-up commands (make demo, make test) and the rest of the workflow (make check, bench, addon...).
# SPDX-License-Identifier: GPL-3.0-or-later
SHELL := /bin/bash
BUILD ?= build
ASAN_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
JOBS ?= $(shell nproc)
UID_NOW := $(shell id -u)
SUDO := $(if $(filter 0,$(UID_NOW)),,sudo)
EMPTY :=
SPACE := $(EMPTY) $(EMPTY)
VERSION := $(shell sed -n 's/^project.softshadow VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)

# Every Debian package the build, tests, demo, benchmark and add-on need.
DEB_PACKAGES := build-essential cmake pkg-config libopenimageio-dev openimageio-tools libstb-dev patchelf \
  libopenexr-dev libglm-dev libembree-dev libegl-dev libegl1-mesa-dev libosmesa6-dev \
  libgl1-mesa-dri libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev \
  blender python3-numpy xvfb xauth zip ccache libboost-dev libpolyclipping-dev \
  clang-14 libclang-rt-14-dev clang-format-14 time mmdebstrap nodejs flake8 python3-venv \
  openscad-testing-data

.PHONY: deps build demo check lint test test-native test-asan test-tsan test-blender test-matrix test-fuzz test-farm bench addon clean

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	bash examples/run_demo.sh $(BUILD)

# The fast lane, run first by .ci/run: the build, Python lint, the source checks (include
# layers, one definition per type name) and the native tests but the slow ones, with the sizes
# and sample counts of SS_TEST_QUICK, one process per core (tests/native/run_shards.sh). Under
# 5 minutes on 2 cores; `make test` runs everything. Left out: the whole-image measurements of
# auto and of each method's quality against the reference, and the longest single tests
# (over 6 s on 2 loaded cores; a new slow test goes here).
CHECK_SLOW_TESTS := AutoMeasures.*:SparseCheck.*:ReferenceAdaptive.*:Refinement.*:CameraPassCoverage.*\
  :PaperProperties*:PaperFailures*:OcclusionTexturesTemporal.*:DbufferQuality.*:SweepQuality.*\
  :DbufferLights.*:DbufferFormula.*:DbufferRaw.*:DbufferArtefacts.*:SweepLimits.ShadowJitterUnderAnAnimatedLight
check: build lint
	cd $(BUILD) && ctest --output-on-failure -R SourceChecks
	bash tests/native/run_shards.sh $(BUILD) '-$(subst $(SPACE),,$(CHECK_SLOW_TESTS))' $(JOBS)

# The add-on, the Blender tests and the benchmark scripts (rules and their reasons: .flake8).
lint: deps
	flake8 blender_addon tests bench

test: build
	$(MAKE) --no-print-directory test-native test-fuzz test-blender test-farm test-matrix test-asan test-tsan

test-native:
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The scene loader and compare's EXR reading under libFuzzer (clang-14), FUZZ_SECONDS each.
FUZZ_SECONDS ?= 45
test-fuzz: build
	bash tests/fuzz/run.sh $(BUILD) $(FUZZ_SECONDS)

# The Flamenco job type compiled against a stand-in of the Manager's job-compiler API.
test-farm:
	node --test farm/flamenco/tests/

test-blender:
	bash tests/blender/run.sh $(BUILD)

# The zip in every supported Blender: the host's 3.4, Debian trixie (4.3) / sid (5.x) root file
# systems holding Blender and GL runtime only (built once with mmdebstrap, cached; needs root),
# and 4.2 LTS / 4.5 LTS as PyPI's bpy modules (installed once into cached virtual environments).
test-matrix: addon
	bash tests/matrix/run.sh dist/softshadow-$(VERSION).zip

# The native tests once more under AddressSanitizer + UndefinedBehaviorSanitizer.
test-asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DSS_SANITIZE=ON -DSS_BUILD_BENCH=OFF > /dev/null
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  SS_TEST_QUICK=1 ctest --output-on-failure -j $(JOBS)

# The tests of threads (shutdown and context destroy during renders, the render thread,
# cancellation) once more under ThreadSanitizer.
TSAN_TESTS := GlRendererCache.*:GlRenderThread.*:CApiContext.*:Cancellation.*
test-tsan: deps
	cmake -S . -B $(TSAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DSS_TSAN=ON -DSS_BUILD_BENCH=OFF > /dev/null
	cmake --build $(TSAN_BUILD) -j $(JOBS) --target softshadow_tests
	TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$(CURDIR)/tests/tsan.supp" $(TSAN_BUILD)/softshadow_tests --gtest_filter='$(TSAN_TESTS)'

bench: build
	bash bench/run.sh $(BUILD)

addon: build
	bash blender_addon/package.sh $(BUILD) $(VERSION)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out dist
