# shanshui: the two commands of the README, each doing its own set-up.
#   make demo   the sample scene rendered headless (still + camera path), results in out/
#   make test   build and run the whole test suite (CTest)
#   make bench  error against run time for every stage, tables and plots in out/bench/
BUILD ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all setup configure build test test-asan test-sanitizers fuzz demo bench format clean

all: build

setup:
	@./scripts/setup.sh

$(BUILD)/build.ninja: CMakeLists.txt | setup
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS)

configure: setup $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The same suite under AddressSanitizer + UndefinedBehaviorSanitizer, in its own tree.
test-asan:
	$(MAKE) test BUILD=build-asan BUILD_TYPE=RelWithDebInfo CMAKE_FLAGS="-DSHANSHUI_SANITIZE=ON -DSHANSHUI_BUILD_BENCH=OFF"

# What .ci/run checks under AddressSanitizer + UBSan on every submission: every library's
# unit and GL tests, the parsers' fuzz replays and the stability suite (which runs every
# tool on stiff input and faults), in build-sanitizers/ at -O1 with line tables only, so that it
# fits beside the Release suite. Left to make test-asan: the end-to-end CLI tests, the three
# tests that repeat the CGAL stages over every sample mesh, and the parameterisation tests
# that judge its time budget (a sanitizer's slowdown changes what the budget allows).
SANITIZER_TESTS = test_core test_image test_mesh test_terrain test_render test_texsynth test_pigment \
  test_strokes test_param test_elements test_scene test_ink test_noise test_view test_stability \
  $(foreach f,obj ply off gltf glb fbx dae stl dem asc geotiff scene manifest png jpg tif pgm,fuzz_replay_$(f))
SANITIZER_SKIP = _NOT_BUILT|EveryCgalTestMesh|Charts.CowMeetsTheAtlasTargets|Parameterize.Auto|Parameterize.ClosedSphere
test-sanitizers:
	$(MAKE) configure BUILD=build-sanitizers BUILD_TYPE=RelWithDebInfo CMAKE_FLAGS="-DSHANSHUI_SANITIZE=ON \
	  -DSHANSHUI_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO='-O1 -g1 -DNDEBUG' \
	  -DCMAKE_C_FLAGS_RELWITHDEBINFO='-O1 -g1 -DNDEBUG'"
	cmake --build build-sanitizers -j $(JOBS) --target $(SANITIZER_TESTS)
	ctest --test-dir build-sanitizers --output-on-failure -j $(JOBS) -LE 'e2e|style' -E '$(SANITIZER_SKIP)'

# Each parser's libFuzzer target for FUZZ_SECONDS (default 30) with clang, ASan and UBSan, in
# build-fuzz/; the test suite replays fuzz/corpus and fuzz/regressions on every run.
fuzz:
	@./scripts/setup.sh fuzz
	./scripts/fuzz.sh

demo: build
	$(BUILD)/bin/shanshui-demo --samples samples --out out \
	  $(if $(wildcard ../shared/data/textures/ink_landscape_scan.jpg),--reference ../shared/data/textures/ink_landscape_scan.jpg)
	@echo
	@echo "demo results in $(CURDIR)/out/ (a second run reuses every stage whose inputs are unchanged):"
	@echo "  out/report.md            pictures, per-stage times and quality numbers, the stability table"
	@echo "  out/stability/           the stability suite's table of cases and outcomes (.md, .csv)"
	@echo "  out/painting.png         the painting sample (ranges, trees, buildings, water) on the chain's own assets"
	@echo "  out/mountain.png         the sample scene's style on the chain's mesh alone"
	@echo "  out/orbit_*.png          an orbit around it"
	@echo "  out/assets/              enhanced sample, quilted wrinkle texture, meshes, UVs, reports"

# Error against run time for every approximate stage: tables, plots and an index in out/bench/.
bench: build
	$(BUILD)/bin/shanshui-bench --stage all --out out/bench
	@echo "bench results: $(CURDIR)/out/bench/README.md"

# Rewrites every C++ source to .clang-format's layout (CTest's style.clang_format checks it).
format:
	git ls-files -z 'apps/*.cpp' 'apps/*.h' 'libs/*.cpp' 'libs/*.h' 'tools/*.cpp' 'tools/*.h' 'tests/*.cpp' \
	  'tests/*.h' 'bench/*.cpp' 'bench/*.h' 'fuzz/*.cpp' 'fuzz/*.h' | xargs -0 clang-format -i

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
