# roadbrdf quick start: `make demo` and `make test` (each installs what is missing first).
BUILD ?= build
JOBS ?= $(shell nproc)
PYTHON ?= /usr/bin/python3
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON)

.PHONY: deps configure build build-app demo test bench clean

deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The program and the Python module only (what the demo runs).
build-app: configure
	cmake --build $(BUILD) -j $(JOBS) --target roadbrdf _roadbrdf

demo: build-app
	bash examples/demo.sh $(BUILD)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	bash bench/run.sh $(BUILD)

clean:
	rm -rf $(BUILD)
