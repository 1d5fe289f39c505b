# roadbrdf quick start: `make demo` and `make test` (each installs the Debian packages it lacks first).
BUILD ?= build
JOBS ?= $(shell nproc)
PYTHON ?= /usr/bin/python3
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(PYTHON)

.PHONY: deps deps-app configure build build-app demo test configure-sanitize test-sanitize test-sanitize-ci fuzz bench install clean \
  format tidy docs

# Package sets of packages.txt: the demo needs [build] and [python], the tests every set.
deps:
	@bash scripts/install-deps.sh

deps-app:
	@bash scripts/install-deps.sh build python

# Configuring an existing build folder again takes seconds; the demo's does not need the test packages.
# The benchmarks are not tests: `make test` leaves them out, `make bench` builds them (BENCHMARKS=ON).
# `make demo` and `make test` configure the same build folder with the same compile flags (warnings are
# errors with g++ 12, CI's compiler, in both: CMakeLists.txt ROADBRDF_WERROR), so `make test` after
# `make demo` compiles only the tests. Turning the tests on changes no flag of the library or program.
BENCHMARKS ?= OFF
configure: deps
	@mkdir -p $(BUILD)
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DROADBRDF_BUILD_TESTS=ON -DROADBRDF_BUILD_BENCHMARKS=$(BENCHMARKS) \
	  > $(BUILD)/configure.log || { cat $(BUILD)/configure.log; exit 1; }

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

# The whole suite (C++ and Python) built with clang 14, AddressSanitizer and UBSan, no recovery: any
# sanitizer report fails its test. Debug with -Werror (clang's warnings at the project's level are
# errors here) and line tables only (sanitizer reports keep file:line; full debug info doubles the
# link time). Python loads the ASan runtime through LD_PRELOAD (set by
# tests/CMakeLists.txt for the python.* tests). The install checks are left out: they build and install
# a separate, unsanitized copy.
SANITIZE_BUILD ?= build-sanitize
SANITIZE_CXX ?= clang++-14
SANITIZE_ENV = UBSAN_OPTIONS=print_stacktrace=1
configure-sanitize: deps
	@mkdir -p $(SANITIZE_BUILD)
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=$(SANITIZE_CXX) \
	  -DCMAKE_CXX_FLAGS=-Werror -DCMAKE_CXX_FLAGS_DEBUG=-gline-tables-only \
	  -DPYTHON_EXECUTABLE=$(PYTHON) -DROADBRDF_SANITIZE=address,undefined -DROADBRDF_FUZZ=ON \
	  -DROADBRDF_BUILD_TESTS=ON -DROADBRDF_BUILD_BENCHMARKS=OFF > $(SANITIZE_BUILD)/configure.log || { cat $(SANITIZE_BUILD)/configure.log; exit 1; }

test-sanitize: configure-sanitize
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -E '^install\.'

# The sanitized subset CI runs after `make test` (the whole sanitized suite does not fit in CI's time
# budget; see docs/ARCHITECTURE.md "Tests"): the CLI built with clang 14, ASan and UBSan, every
# parser's fuzz corpus (seeds and every crash once found) replayed through the libFuzzer program (the
# sanitized build is a fuzzing build, -DROADBRDF_FUZZ=ON, so CI builds the fuzzers) and the CLI's
# adversarial and data-loss tests.
# The Python module is built too, so that CI compiles the library, the program and the module in a
# Debug configuration with -Werror (clang 14) as well as in the Release one (g++ 12).
SANITIZE_CI_TARGETS = roadbrdf _roadbrdf cli_adversarial_test cli_data_loss_test fuzzers
SANITIZE_CI_TESTS = ^(fuzz_corpus[.]|CliAdversarial[.]|CliDataLoss[.])
test-sanitize-ci: configure-sanitize
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target $(SANITIZE_CI_TARGETS)
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -R '$(SANITIZE_CI_TESTS)'

# libFuzzer programs of tests/fuzz in build-fuzz (clang 14, ASan + UBSan), each run for FUZZ_SECONDS
# on a copy of its corpus; crashes are written to build-fuzz/crashes/<name>/ (add them to the corpus
# as regression inputs once fixed).
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 20
fuzz: deps
	@mkdir -p $(FUZZ_BUILD)
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=$(SANITIZE_CXX) \
	  -DROADBRDF_FUZZ=ON -DROADBRDF_SANITIZE=address,undefined -DROADBRDF_BUILD_TESTS=OFF \
	  -DROADBRDF_BUILD_PYTHON=OFF -DROADBRDF_BUILD_BENCHMARKS=OFF > $(FUZZ_BUILD)/configure.log \
	  || { cat $(FUZZ_BUILD)/configure.log; exit 1; }
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzzers
	bash tests/fuzz/run_fuzzers.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

bench:
	$(MAKE) build BENCHMARKS=ON
	bash bench/run.sh $(BUILD)

# Install into PREFIX (default /usr/local); see README "Install".
PREFIX ?= /usr/local
install: build-app
	cmake --build $(BUILD) -j $(JOBS) --target roadbrdf_manpage
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD)

# docs/models.md from the models' metadata: the build writes $(BUILD)/docs/models.md with the
# program; this copies it over the committed one (a test fails while they differ).
docs:
	cmake --build $(BUILD) --target update_models_reference

# C++ style (.clang-format): `make format` applies it to every C++ file; ctest style.clang_format
# (part of `make test`) fails when a file differs.
format:
	bash scripts/check_format.sh . --fix

# Static analysis (.clang-tidy: bugprone, performance, cognitive complexity) of every library,
# program and Python-module source; any finding is an error. clang-tidy reads the compile database
# of a configuration without precompiled headers ($(TIDY_BUILD); configuring it builds nothing):
# it cannot load GCC's. Takes 10-20 s per file (about half an hour for the tree on two cores), so CI
# does not run it: run it before a change lands.
TIDY_BUILD ?= build-tidy
TIDY_FILES = '(src|python/src)/.*\.cpp$$'
tidy: deps
	@mkdir -p $(TIDY_BUILD)
	cmake -S . -B $(TIDY_BUILD) $(CMAKE_FLAGS) -DROADBRDF_PRECOMPILE_HEADERS=OFF -DROADBRDF_BUILD_TESTS=OFF \
	  -DROADBRDF_BUILD_BENCHMARKS=OFF > $(TIDY_BUILD)/configure.log || { cat $(TIDY_BUILD)/configure.log; exit 1; }
	run-clang-tidy-14 -quiet -p $(TIDY_BUILD) -j $(JOBS) $(TIDY_FILES)
