# roadbrdf quick start: `make demo` and `make test` (each installs the Debian packages it lacks first).
BUILD ?= build
JOBS ?= $(shell nproc)
PYTHON ?= /usr/bin/python3
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON)

.PHONY: deps deps-app configure build build-app demo test bench install clean

# Package sets of packages.txt: the demo needs [build] and [python], the tests every set.
deps:
	@bash scripts/install-deps.sh

deps-app:
	@bash scripts/install-deps.sh build python

# Configuring an existing build folder again takes seconds; the demo's does not need the test packages.
configure: deps
	@mkdir -p $(BUILD)
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DROADBRDF_BUILD_TESTS=ON -DROADBRDF_BUILD_BENCHMARKS=ON > $(BUILD)/configure.log \
	  || { cat $(BUILD)/configure.log; exit 1; }

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The program and the Python module only (what the demo runs).
build-app: deps-app
	@mkdir -p $(BUILD)
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DROADBRDF_BUILD_TESTS=OFF -DROADBRDF_BUILD_BENCHMARKS=OFF > $(BUILD)/configure.log \
	  || { cat $(BUILD)/configure.log; exit 1; }
	cmake --build $(BUILD) -j $(JOBS) --target roadbrdf _roadbrdf

demo: build-app
	bash examples/demo.sh $(BUILD)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	bash bench/run.sh $(BUILD)

# Install into PREFIX (default /usr/local); see README "Install".
PREFIX ?= /usr/local
install: build-app
	cmake --build $(BUILD) -j $(JOBS) --target roadbrdf_manpage
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD)
