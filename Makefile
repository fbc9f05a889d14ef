# The two commands of the README's quick start, on a fresh Debian 12 machine:
#   make demo   — install what is missing, build, and run the main job on embedded synthetic data
#   make test   — install what is missing, build, and run the whole CTest suite
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps configure build app test test-long demo clean

all: build

deps:
	@./scripts/install-deps.sh

# Configure once; later builds reuse the tree (CMake re-runs itself when a CMakeLists changes).
$(BUILD_DIR)/CMakeCache.txt: | deps
	cmake --preset release -B $(BUILD_DIR) $(CMAKE_FLAGS)

configure: deps $(BUILD_DIR)/CMakeCache.txt

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The CLI and the plugins only: all the demo needs.
app: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target app

# Fast by default; checks that take minutes carry the CTest label `long`.
test: build
	@./scripts/install-deps.sh --test
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE long

test-long: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L long

demo: app
	./scripts/demo.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR)
