# shanshui: the two commands of the README, each doing its own set-up.
#   make demo   the sample scene rendered headless (still + camera path), results in out/
#   make test   build and run the whole test suite (CTest)
BUILD ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all setup configure build test test-asan demo format clean

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

SCENE ?= samples/scenes/default.json

demo: build
	@mkdir -p out
	$(BUILD)/bin/shanshui-render $(SCENE) -o out/mountain.png --stats out/mountain_stats.json
	$(BUILD)/bin/shanshui-render $(SCENE) -o out/path.png --size 640x480 --frames 12 --stats out/path_stats.json
	@echo
	@echo "demo results in $(CURDIR)/out/:"
	@echo "  out/mountain.png         the sample scene, painted headless"
	@echo "  out/path_0000..0011.png  frames along the scene's camera path"
	@echo "  out/*_stats.json         passes built, shader variants, per-frame GPU time per pass"

format:
	find apps libs tools tests bench -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) build-asan out
