# shanshui: the two commands of the README, each doing its own set-up.
#   make demo   DEM -> mountain mesh -> headless render, results in out/
#   make test   build and run the whole test suite (CTest)
BUILD ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
SAMPLE_DEM ?= samples/terrain/mount_st_helens.dem

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

demo: build
	@mkdir -p out
	$(BUILD)/bin/shanshui-terrain $(SAMPLE_DEM) -o out/mount_st_helens.obj --max-vertices 200000
	$(BUILD)/bin/shanshui-render out/mount_st_helens.obj -o out/mount_st_helens.png --size 1280x800 --elevation 30 --zoom 1.6
	@echo
	@echo "demo results in $(CURDIR)/out/:"
	@echo "  out/mount_st_helens.obj   mountain mesh from the USGS DEM"
	@echo "  out/mount_st_helens.png   headless render of it"

format:
	find apps libs tools tests bench -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) build-asan out
