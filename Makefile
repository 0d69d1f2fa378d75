# The two user commands. Each installs what is missing, configures, builds and does its job.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
DEFORM_TEST_MESHES ?=
export DEFORM_TEST_MESHES

.PHONY: all setup build demo test format clean

all: build

setup:
	@bash tools/setup.sh

build: setup
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@bash tools/demo.sh $(BUILD_DIR)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	@rm -rf $(BUILD_DIR)
