# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# The one entry point. `make help` lists the targets.
BOARD    ?= mclv
MOTOR    ?= hurst
SCENARIO ?= default
IMAGE    ?= drive
BUILD    ?= build
JOBS     ?= $(shell nproc 2>/dev/null || echo 2)

CMAKE_DEFS := -DBOARD=$(BOARD) -DMOTOR=$(MOTOR)
CTEST      := ctest --output-on-failure -j $(JOBS)

HOST_DIR  := $(BUILD)/host
ASAN_DIR  := $(BUILD)/asan
COV_DIR   := $(BUILD)/cov
CLANG_DIR := $(BUILD)/clang
# Coverage is gcc's (gcov data, and the gates count gcc's branches) whatever CC
# says; the second compiler of make test is clang.
COV_CC   ?= gcc
CLANG_CC ?= clang

# BOARD and MOTOR name headers; without this, a misspelt name would build and
# check the defaults (UserParms.h's #else) and report success. One line, before
# anything runs, for every goal that uses them.
PROFILE_GOALS := build unit asan coverage check-16bit lint format bench sim firmware test test-clang
ifneq ($(filter $(PROFILE_GOALS),$(MAKECMDGOALS)),)
ifeq ($(wildcard boards/board_$(BOARD).h),)
$(error BOARD=$(BOARD): no boards/board_$(BOARD).h (boards: $(patsubst boards/board_%.h,%,$(wildcard boards/board_*.h))))
endif
ifeq ($(wildcard firmware/motors/motor_$(MOTOR).h),)
$(error MOTOR=$(MOTOR): no firmware/motors/motor_$(MOTOR).h (motors: $(patsubst firmware/motors/motor_%.h,%,$(wildcard firmware/motors/motor_*.h))))
endif
endif

.PHONY: help bootstrap build unit asan coverage check-16bit cycles size lint format bench sim robust firmware test test-clang clean

help:
	@echo "make sim          run the firmware core against the simulated motor (SCENARIO=, MOTOR=, BOARD=)"
	@echo "make sim PTY=1    the same motor behind X2Cscope on a pty (and TCP 12666), for tools/scope"
	@echo "make test         everything CI runs: bootstrap, lint, check-16bit, cycles, size, coverage, sanitized, clang and plain tests"
	@echo "make unit         build and run the host tests (plain build)"
	@echo "make test-clang   build with clang in $(CLANG_DIR) and run the unit tests"
	@echo "make asan         build and run the host tests under ASan + UBSan"
	@echo "make coverage     gcovr HTML report in $(COV_DIR)/coverage/, fails below the gates"
	@echo "make check-16bit  core built with avr-gcc (16-bit int), run in simavr, compared bit for bit with the PC"
	@echo "make cycles       cycle guard: AVR cycles of mc_step per state (simavr) against committed ceilings"
	@echo "make size         size guard: avr-gcc flash and RAM of the dsPIC image's sources per part against ceilings"
	@echo "make lint         cppcheck + clang-format check; ruff + mypy (strict) on tools/ and test/ Python"
	@echo "make format       clang-format the sources in place (and ruff's safe fixes)"
	@echo "make bench        instructions per call (callgrind) and avr-gcc RAM/flash of each block"
	@echo "make robust       randomized campaign: RUNS= per profile (default 400) on three profiles, report and plots in $(BUILD)/robust/"
	@echo "make firmware     dsPIC image with XC16 (needs XC16_DIR or xc16-gcc on PATH); IMAGE=identify: the commissioning image"
	@echo "make clean        remove $(BUILD)/"
	@echo "variables: BOARD=$(BOARD) MOTOR=$(MOTOR) SCENARIO=$(SCENARIO) IMAGE=$(IMAGE) JOBS=$(JOBS)"

bootstrap:
	@tools/bootstrap

# ---- host builds ----------------------------------------------------------
# Every goal that needs a tool or library first makes sure it is here
# (tools/bootstrap: instant once installed), so each works from a fresh clone.
$(HOST_DIR)/Makefile $(HOST_DIR)/CMakeCache.txt: CMakeLists.txt | bootstrap
	cmake -S . -B $(HOST_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_DEFS) >/dev/null

build: bootstrap $(HOST_DIR)/CMakeCache.txt
	cmake -S . -B $(HOST_DIR) $(CMAKE_DEFS) >/dev/null
	cmake --build $(HOST_DIR) -j $(JOBS)

unit: build
	cd $(HOST_DIR) && $(CTEST)

asan: bootstrap
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DFOC_SANITIZE=ON $(CMAKE_DEFS) >/dev/null
	cmake --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 $(CTEST) -LE slow

coverage: bootstrap
	cmake -S . -B $(COV_DIR) -DCMAKE_C_COMPILER=$(COV_CC) -DCMAKE_BUILD_TYPE=Debug -DFOC_COVERAGE=ON $(CMAKE_DEFS) >/dev/null
	cmake --build $(COV_DIR) -j $(JOBS)
	find $(COV_DIR) -name '*.gcda' -delete
	@# The report and the gates run even when a test fails; the target fails either way.
	(cd $(COV_DIR) && $(CTEST) -LE slow); status=$$?; tools/coverage_gate $(COV_DIR) && exit $$status

# The second compiler: the same strict flags (CMakeLists.txt), the unit tests
# (the closed-loop ones, label slow, run in the plain build).
test-clang: bootstrap
	cmake -S . -B $(CLANG_DIR) -DCMAKE_C_COMPILER=$(CLANG_CC) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_DEFS) >/dev/null
	cmake --build $(CLANG_DIR) -j $(JOBS)
	cd $(CLANG_DIR) && $(CTEST) -L unit

check-16bit: bootstrap
	@BOARD=$(BOARD) MOTOR=$(MOTOR) tools/check16/run $(BUILD)/check16

cycles: bootstrap
	@BOARD=mclv MOTOR=hurst tools/check16/cycles $(BUILD)/cycles  # the ceilings are for this profile

size: bootstrap
	@BOARD=mclv MOTOR=hurst tools/check16/size $(BUILD)/size  # the ceilings are for this profile

lint: bootstrap
	@BOARD=$(BOARD) MOTOR=$(MOTOR) tools/lint

format: bootstrap
	@BOARD=$(BOARD) MOTOR=$(MOTOR) tools/lint --fix

bench: bootstrap build
	@tools/bench/run $(HOST_DIR) $(BUILD)/bench

# PTY=1: no scenario, the X2Cscope target on a pseudo-terminal and TCP 12666 (docs/x2cscope.md).
sim: bootstrap build
	@$(if $(PTY),$(HOST_DIR)/tools/sim/sim --pty --tcp 12666 --motor $(MOTOR) --board $(BOARD),tools/sim/run $(HOST_DIR) $(SCENARIO) $(MOTOR) $(BOARD))

# The randomized campaign (docs/robustness.md); its quick subset runs in make test (robust_quick).
RUNS ?= 400
SEED ?= 1
robust: bootstrap
	@tools/robust/run $(BUILD)/robust $(RUNS) $(SEED)

firmware:
	@+FIRMWARE_OUT=$(BUILD)/firmware tools/firmware_build $(if $(findstring n,$(firstword -$(MAKEFLAGS))),--print) --image $(IMAGE) $(BOARD) $(MOTOR)

# The plain suite runs last so the output closes on CTest's summary line.
test: bootstrap
	@$(MAKE) --no-print-directory lint
	@$(MAKE) --no-print-directory check-16bit
	@$(MAKE) --no-print-directory cycles
	@$(MAKE) --no-print-directory size
	@$(MAKE) --no-print-directory coverage
	@$(MAKE) --no-print-directory asan
	@$(MAKE) --no-print-directory test-clang
	@$(MAKE) --no-print-directory unit

clean:
	rm -rf $(BUILD)
