# The two commands of the README.  Everything else is CMake + ctest.
#   make run   install deps, build, run the default sweep (results/latest/report.html)
#   make test  install deps, build, run every test through ctest (what CI runs)
#   make check install deps, build, run the quick tier (ctest -L quick: unit
#              tests and fast end-to-end checks, no Valgrind, no sanitizer
#              build, no fuzzing; <= 3 min on two cores): the inner loop
#   make install [PREFIX=/usr/local]  binary, man page, bash/zsh completions
BUILD ?= build
JOBS  ?= $(shell nproc)
# ctest's jobs: one more than the cores.  The suite's tests wait for part of
# their time (watchdogs, Xvfb, the Slurm daemons, the browser), which left
# the two cores idle 6 % of the test phase at -j 2; a third job fills that
# (docs/testing.md, "What the suite costs").
TEST_JOBS ?= $(shell echo $$(( $$(nproc) + 1 )))
CTEST_ARGS ?=
PREFIX ?= /usr/local

.PHONY: all deps build run test check install clean

all: build

deps:
	@bash scripts/install-deps

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo > $(BUILD).cmake.log 2>&1 || (cat $(BUILD).cmake.log; exit 1)
	@# quiet when nothing failed: the log holds the progress lines, and a
	@# failed build prints its last 60 lines (the compiler's error is there)
	@echo "building $(BUILD)/ (log: $(BUILD).build.log)"
	@MAKEFLAGS=--no-print-directory cmake --build $(BUILD) -j $(JOBS) > $(BUILD).build.log 2>&1 || \
	  (tail -n 60 $(BUILD).build.log; echo "build failed: the whole log is $(BUILD).build.log"; exit 1)

run: build
	@./$(BUILD)/dmbench run

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(TEST_JOBS) $(CTEST_ARGS)

check: build
	@cd $(BUILD) && ctest --output-on-failure -j $(TEST_JOBS) -L quick $(CTEST_ARGS)

install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(BUILD).cmake.log $(BUILD).build.log
