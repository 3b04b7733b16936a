# Front door: `make demo` and `make test` install their own dependencies.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release
MAKEFLAGS += --no-print-directory

.PHONY: deps configure build demo install test bench-build bench docs asan-configure asan fuzz clean

deps:
	@./scripts/install-deps.sh

# A new build folder is made for Ninja: it compiles a stage's sources while the stages it links
# against are still compiling, where Make finishes each library first (a cold `make demo` on 2
# cores: 149 s instead of 200 s, the same CPU). A folder keeps the generator it was made with.
generator = $(if $(wildcard $(1)/CMakeCache.txt),,-G Ninja)

configure: deps
	@cmake -S . -B $(BUILD) $(call generator,$(BUILD)) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The demo needs only the command-line tool.
demo: configure
	@cmake --build $(BUILD) -j $(JOBS) --target lagrange
	@mkdir -p out
	$(BUILD)/lagrange simulate examples/double_pendulum.yaml -o out/double_pendulum.csv --plot out/double_pendulum.svg

# Installs the command, the headers, the libraries and the docs under PREFIX (bin/, include/,
# lib/, share/doc/lagrange/) and the Python module (lib/python3.X/dist-packages/lagrange, found
# by Debian's python3 under /usr/local; docs/python.md); only these and their libraries are built.
PREFIX ?= /usr/local
install: configure
	@cmake --build $(BUILD) -j $(JOBS) --target lagrange_installables
	@cmake --install $(BUILD) --prefix $(PREFIX)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The benchmarks, built and not run: CI builds them after the tests, so that an API change cannot
# leave them broken (`make bench` builds and runs them).
bench-build: configure
	@cmake --build $(BUILD) -j $(JOBS) --target benchmarks

# The HTML manual (docs/: Sphinx, furo, myst-parser, all Debian's) into $(BUILD)/docs/html,
# offline; a Sphinx warning is an error. It needs the command (the command-line reference is
# its own --help) and the Python module (the API reference is its docstrings; the notebooks of
# docs/notebooks run on it, and a cell that raises fails the build); Doxygen and breathe
# render the C++ reference from include/lagrange.
docs: configure
	@LAGRANGE_DOCS=1 ./scripts/install-deps.sh
	@cmake --build $(BUILD) -j $(JOBS) --target lagrange _lagrange
	@LAGRANGE_BUILD=$(BUILD) /usr/bin/python3 -m sphinx -W --keep-going -q -b html \
	  -d $(BUILD)/docs/doctrees docs $(BUILD)/docs/html
	@echo "docs: $(BUILD)/docs/html/index.html"

bench: build bench-build
	@LAGRANGE_BENCH=1 ./scripts/install-deps.sh
	@./bench/run.sh $(BUILD)

# AddressSanitizer + UndefinedBehaviorSanitizer: clang, Debug at -O1 (sanitized -O0 GiNaC code is
# too slow) with line tables only (file:line in reports at a fraction of full -g's compile and link
# time); the library, the CLI and the tests, then the whole test suite under the sanitizers. The
# same build holds the libFuzzer targets (`make fuzz`), so the library is compiled once for both.
# The build has the sanitizer settings too, for a build with LAGRANGE_TEST_SHARDS=OFF, where
# gtest_discover_tests runs each test binary to list it.
ASAN_BUILD ?= build-asan
# symbolize=0: matching LeakSanitizer's CLN suppression by module name needs no symbolizer, and
# starting llvm-symbolizer at every test's exit doubled the suite's cost. A test that fails is run
# again with symbolize=1, so its report names functions and lines.
ASAN_OPTS = detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
SANITIZER_ENV = ASAN_OPTIONS=$(ASAN_OPTS):symbolize=0 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/.ci/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
SANITIZER_ENV_SYMBOLIZED = $(SANITIZER_ENV) ASAN_OPTIONS=$(ASAN_OPTS):symbolize=1
# Left out of the sanitizer run (they run in the Release suite): the heaviest repetitions of paths
# that lighter tests take under the sanitizers too — the Panda (the UR5 and the elbow arm cover the
# same code), the longest chains of the scaling tests (the short ones run), the 300-link URDF (the
# 200-link chain runs), a kill-timing loop, the kite power cycle (its transcription and Hessian are
# checked on the smaller problems; its power curve's sweep logic on the rotor) and the rigid AP2's
# derivative checks and homotopy (the stages' code on the double integrator). About 400 of the 2300
# test-seconds under ASan. A gtest filter
# (GTEST_FILTER=-$(ASAN_SKIP)): the sanitizer build runs each test executable in a few shards,
# not one process per test (tests/CMakeLists.txt, LAGRANGE_TEST_SHARDS).
ASAN_SKIP ?= *Panda*:*panda*:*PowerCycle*:*power_cycle_ap2*:*KitesPowerCurve*:*KillDuringALongWrite*:*GrowsLinearlyWithTheChain*:$\
*RecursiveChain.MatchesTheClosedFormPendulum/4:*RecursiveChain.MatchesTheClosedFormPendulum/5:$\
*AThreeHundredLinkUrdf*:*SkewSymmetry.*planar_arm_pd*:*Ur5ManipulatorFormIsSkewSymmetric*:$\
*InertiaMatrixOfTheUr5*:*ExportManipulator.Ur5MatchesEval*
# Tests that are not gtest executables, left out by ctest: the manual's commands (a check of the
# documentation; the CLI paths they take run under ASan in their own tests).
ASAN_CTEST_SKIP ?= ^Docs\.

asan-configure:
	@LAGRANGE_FUZZ=1 ./scripts/install-deps.sh
	@CC=clang CXX=clang++ cmake -S . -B $(ASAN_BUILD) $(call generator,$(ASAN_BUILD)) \
	  -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" \
	  -DLAGRANGE_SANITIZE=ON -DLAGRANGE_FUZZ=ON -DLAGRANGE_BUILD_BENCH=OFF -DLAGRANGE_BUILD_PYTHON=OFF >/dev/null

asan: asan-configure
	@$(SANITIZER_ENV) cmake --build $(ASAN_BUILD) -j $(JOBS)
	@cd $(ASAN_BUILD) && { $(SANITIZER_ENV) GTEST_FILTER='-$(ASAN_SKIP)' ctest -j $(JOBS) \
	    -E '$(ASAN_CTEST_SKIP)' || \
	  { echo "asan: the failed tests again, with symbolised reports:"; \
	    $(SANITIZER_ENV_SYMBOLIZED) GTEST_FILTER='-$(ASAN_SKIP)' ctest --rerun-failed --output-on-failure; \
	    exit 1; }; }

# libFuzzer targets of the model reader (fuzz/), in the sanitizer build; each runs FUZZ_SECONDS
# (or exactly FUZZ_RUNS inputs from a fixed seed, reproducibly, as CI does) on its corpus (seeded
# from examples/ and fuzz/corpus/), JOBS targets at a time. Findings land in
# $(ASAN_BUILD)/fuzz/artifacts/.
FUZZ_SECONDS ?= 600
FUZZ_RUNS ?=
FUZZ_RUNS_MODEL ?=
FUZZ_RUNS_EXPRESSION ?=
FUZZ_RUNS_URDF ?=
FUZZ_RUNS_SWEEP_SPEC ?=
FUZZ_RUNS_METRIC ?=
fuzz: asan-configure
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target fuzz_model fuzz_expression fuzz_urdf \
	  fuzz_sweep_spec fuzz_metric
	@FUZZ_RUNS=$(FUZZ_RUNS) FUZZ_RUNS_MODEL=$(FUZZ_RUNS_MODEL) FUZZ_RUNS_EXPRESSION=$(FUZZ_RUNS_EXPRESSION) \
	  FUZZ_RUNS_URDF=$(FUZZ_RUNS_URDF) FUZZ_RUNS_SWEEP_SPEC=$(FUZZ_RUNS_SWEEP_SPEC) \
	  FUZZ_RUNS_METRIC=$(FUZZ_RUNS_METRIC) FUZZ_JOBS=$(JOBS) \
	  ./fuzz/run.sh $(ASAN_BUILD) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD) out
