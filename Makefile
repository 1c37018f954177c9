# CHASM-AUV: setup, build, test and demo in one command each.
#
#   make          set up .venv, generate the LCM types, build C/C++ and the types jar
#   make test     everything above, the Python lint (`make lint`), then the whole test suite (tests/)
#   make demo     MCM team (3 search + 1 reacquire-identify over the acoustic link): report and plots in build/demo
#   make spy      lcm-spy with the project's types on its classpath
#   make bench    benchmarks (bench/), printing figures
#   make format   reformat the Python (ruff)
#   make clean    remove build/ (keeps .venv; `make distclean` removes it too)
#
# Every output goes under build/. Nothing here needs sudo.

SHELL := /bin/bash
.DEFAULT_GOAL := all
.DELETE_ON_ERROR:

# Build on every core unless the caller chose with -j: a clean `make test`
# compiles the C/C++ twice (normal and sanitized), 9 of its 15 minutes on
# 2 cores when serial.
ifeq ($(filter -j%,$(MAKEFLAGS)),)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 2)
endif

PYTHON ?= python3
VENV := .venv
VPY := $(VENV)/bin/python
BUILD := build
VENV_STAMP := $(VENV)/.requirements.stamp

# ---------------------------------------------------------------- virtualenv
# The pinned dependencies, then the project itself (pyproject.toml) in
# editable mode: the console commands (auv-demo, auv-launch, ...) and
# `python -m sim` run the checkout's code with no path set by hand.
$(VENV_STAMP): requirements.txt pyproject.toml
	@test -x $(VPY) || $(PYTHON) -m venv $(VENV) || { \
	  echo "error: '$(PYTHON) -m venv' failed: install python3-venv (Debian/Ubuntu: apt install python3-venv)" >&2; exit 1; }
	$(VPY) -m pip install --quiet --disable-pip-version-check -r requirements.txt
	$(VPY) -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e .
	@touch $@

# Paths inside the lcm and cmeel-eigen wheels, found once after install.
$(BUILD)/config.mk: $(VENV_STAMP) python/tools/codegen/wheel_paths.py
	@mkdir -p $(BUILD)
	$(VPY) python/tools/codegen/wheel_paths.py > $@

ifeq ($(filter clean distclean,$(MAKECMDGOALS)),)
-include $(BUILD)/config.mk
endif

LCM_GEN := $(LCM_BIN)/lcm-gen
LCM_JAR := $(LCM_PREFIX)/share/java/lcm.jar

# ---------------------------------------------------------------- LCM types
LCM_FILES := $(sort $(wildcard lcmtypes/*.lcm))
LCM_TYPES := $(basename $(notdir $(LCM_FILES)))
GEN := $(BUILD)/gen
GEN_C_STAMP := $(GEN)/c.stamp
GEN_PY_STAMP := $(GEN)/python.stamp
GEN_C_SRCS := $(patsubst %,$(GEN)/c/auv_%.c,$(LCM_TYPES)) $(GEN)/c/auv_type_table.c

# The C links OpenSSL's libcrypto (command authentication, docs/security.md):
# its headers come with Debian's libssl-dev, installed here when this is root
# with apt-get (as apt_test_tool does for the test tools), else a clear error.
OPENSSL_STAMP := $(BUILD)/.openssl.stamp
have_openssl = echo '\#include <openssl/hmac.h>' | $(CC) -E -x c - >/dev/null 2>&1
$(OPENSSL_STAMP):
	@mkdir -p $(@D)
	@$(have_openssl) || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  { echo "installing libssl-dev (apt-get) for libcrypto's headers"; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libssl-dev >/dev/null 2>&1 || \
	    { apt-get update >/dev/null 2>&1 && \
	      DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libssl-dev >/dev/null 2>&1; }; }; } ; \
	  $(have_openssl) || { echo "error: OpenSSL's headers (openssl/hmac.h) not found: install libssl-dev" \
	    "(Debian/Ubuntu: sudo apt install libssl-dev; Fedora: openssl-devel)" >&2; exit 1; }
	@touch $@

$(GEN_C_STAMP): $(LCM_FILES) $(BUILD)/config.mk python/tools/codegen/gen_type_table.py $(OPENSSL_STAMP)
	@rm -rf $(GEN)/c && mkdir -p $(GEN)/c/auv
	@echo "lcm-gen C    -> $(GEN)/c"
	@$(LCM_GEN) -c --c-typeinfo --c-cpath $(GEN)/c --c-hpath $(GEN)/c/auv --cinclude auv $(LCM_FILES)
	@$(VPY) python/tools/codegen/gen_type_table.py $(LCM_FILES) > $(GEN)/c/auv_type_table.c
	@touch $@
$(GEN_C_SRCS): $(GEN_C_STAMP) ;

# The generated package `auv` is importable in .venv through a .pth file
# (the one way Python adds a folder to an environment); a second build tree
# (`make BUILD=x`) points it there, and tests of any tree set PYTHONPATH.
$(GEN_PY_STAMP): $(LCM_FILES) $(BUILD)/config.mk
	@rm -rf $(GEN)/python && mkdir -p $(GEN)/python
	@echo "lcm-gen Python -> $(GEN)/python"
	@$(LCM_GEN) -p --ppath $(GEN)/python $(LCM_FILES)
	@echo "$(abspath $(GEN)/python)" > "$$($(VPY) -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/chasm_auv_types.pth"
	@touch $@

# lcm-spy finds types by fingerprint on its classpath: one jar of every type.
TYPES_JAR := $(BUILD)/java/auv_types.jar
$(TYPES_JAR): $(LCM_FILES) $(BUILD)/config.mk
	@command -v javac >/dev/null || { echo "error: javac not found: the types jar for lcm-spy needs a JDK" >&2; exit 1; }
	@rm -rf $(GEN)/java $(BUILD)/java && mkdir -p $(GEN)/java $(BUILD)/java/classes
	@echo "lcm-gen Java + javac -> $(TYPES_JAR)"
	@$(LCM_GEN) -j --jpath $(GEN)/java $(LCM_FILES)
	@javac -nowarn -source 8 -target 8 -Xlint:-options -d $(BUILD)/java/classes -cp $(LCM_JAR) $(GEN)/java/auv/*.java
	@cd $(BUILD)/java/classes && $(abspath $(VPY)) -m zipfile -c ../auv_types.jar auv

# ---------------------------------------------------------------- C / C++
CC ?= cc
CXX ?= c++
OPT ?= -O2 -g
WARN := -Wall -Wextra -Werror
CFLAGS_ALL := -std=c11 -D_DEFAULT_SOURCE $(WARN) $(OPT) -fPIC -Ic -I$(GEN)/c -I$(LCM_INC)
CXXFLAGS_ALL := -std=c++17 $(WARN) $(OPT) -fPIC -Ic -I$(GEN)/c -I$(LCM_INC) -I$(EIGEN_INC)
# lcm-gen's --c-typeinfo output casts size_t(*)(void) to int(*)(void); only its
# generated files get this one warning switched off. lcm_coretypes.h calls
# memcpy(NULL, src, 0) when decoding an empty variable-length byte array (harmless,
# but UBSan's nonnull-attribute check stops on it), so that check is off there too.
GEN_CFLAGS := -Wno-cast-function-type -fno-sanitize=nonnull-attribute
# The sanitized variant at -O1 with line tables only (-g1, enough for ASan's and
# UBSan's file:line): it compiles in two thirds of -O2 -g's time (the C++ filter's
# files most of all), and it comes after OPT on the line, so it wins.
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -O1 -g1
LCM_LDLIBS := -L$(LCM_LIB) -Wl,-rpath,$(LCM_LIB) -llcm
LDLIBS_ALL := -lm -ldl -lpthread -lcrypto

# Two build variants share one set of rules: build/ (normal) and build/san/
# (AddressSanitizer + UndefinedBehaviorSanitizer), so tests can run both.
VARIANTS := $(BUILD) $(BUILD)/san
# Quiet: one line per output; `make V=1` shows whole commands.
Q = $(if $(V),,@echo "  $(if $(filter $(BUILD)/san/%,$@),[san] )$(notdir $@)";)
vflags = $(if $(filter $(BUILD)/san/%,$@),$(SAN_FLAGS))

define variant_rules
$(1)/obj/%.o: %.c Makefile | $(GEN_C_STAMP)
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(CFLAGS_ALL) $$(vflags) -MMD -MP -c $$< -o $$@
$(1)/obj/%.o: %.cpp Makefile | $(GEN_C_STAMP)
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(CXXFLAGS_ALL) $$(vflags) -MMD -MP -c $$< -o $$@
$(1)/obj/gen/%.o: $(GEN)/c/%.c Makefile
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(CFLAGS_ALL) $$(vflags) $$(GEN_CFLAGS) -c $$< -o $$@
$(1)/lib/libauvtypes.a: $(patsubst $(GEN)/c/%.c,$(1)/obj/gen/%.o,$(GEN_C_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/lib/libauvcommon.a: $(patsubst %.c,$(1)/obj/%.o,$(wildcard c/common/*.c))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/auv-lcm-probe: $(1)/obj/c/tools/auv_lcm_probe.o $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/auv-auth-probe: $(1)/obj/c/tools/auv_auth_probe.o $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call variant_rules,$(v))))

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)

# The harness of every C/C++ unit-test program (tests/harness/unit.h): the
# runner and checks; allocation counting (with --wrap=malloc & co.); helpers
# for tests that load plans with libchasm.
UNIT_HARNESS_SRCS := tests/harness/unit.c
UNIT_ALLOC_SRCS := tests/harness/unit_alloc.c
PLAN_TEST_SRCS := tests/harness/plan_test.c

# Programs every variant builds; component makefiles append to these.
C_PROGRAMS := bin/auv-lcm-probe bin/auv-auth-probe
C_LIBS := lib/libauvtypes.a lib/libauvcommon.a

# Components add their rules and append to C_PROGRAMS / C_LIBS here.
COMPONENTS ?= $(sort $(wildcard c/*/component.mk))
-include $(COMPONENTS)

C_OUTPUTS := $(addprefix $(BUILD)/,$(C_PROGRAMS) $(C_LIBS))
SAN_OUTPUTS := $(addprefix $(BUILD)/san/,$(C_PROGRAMS) $(C_LIBS))

# ---------------------------------------------------------------- top targets
HAVE_JAVAC := $(shell command -v javac >/dev/null 2>&1 && echo yes)
JAR_TARGET := $(if $(HAVE_JAVAC),$(TYPES_JAR))

# The Python byte-compiled once, here: where PYTHONDONTWRITEBYTECODE is set
# (some CI environments set it) every process would otherwise compile each
# module it imports, at every start (0.1 s of CPU for a simulator, and a
# test run starts hundreds of processes). Python reads the files either way.
PYC_STAMP := $(BUILD)/.pyc.stamp
$(PYC_STAMP): $(GEN_PY_STAMP) $(shell find python -name '*.py' 2>/dev/null)
	$(VPY) -m compileall -q python $(GEN)/python >/dev/null
	@touch $@

.PHONY: all build sanitize test test-slow lint format demo spy bench clean distclean setup validate stress chromium gpsd
setup: $(VENV_STAMP)
build: $(GEN_PY_STAMP) $(C_OUTPUTS) $(JAR_TARGET) $(PYC_STAMP)
sanitize: $(SAN_OUTPUTS)
all: build

# Tests run in a private network namespace when the kernel allows it (see
# tests/isolated_net.sh): LCM multicast then needs no route on the host and
# test traffic can never leave the machine or meet another run's.
PYTEST_ARGS ?=
# Test-only tools from Debian's packages: chromium (the console's browser tests)
# and gpsd (it reads the GPS emulator's NMEA). Each is installed here, outside
# the tests' private network namespace (which has no network), when this is
# root and it is missing; elsewhere the tests that need it skip and say why.
# $(1): the command, $(2): the package, $(3): what needs it.
define apt_test_tool
	@PATH="$$PATH:/usr/sbin:/sbin" command -v $(1) >/dev/null || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null && \
	  { echo "installing $(2) (apt-get) for $(3)"; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $(2) >/dev/null 2>&1 || \
	    { apt-get update >/dev/null 2>&1 && \
	      DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $(2) >/dev/null 2>&1; }; }; } || \
	  echo "note: $(2) is not installed (not root, or apt-get failed): $(3) will skip"
endef
chromium:
	$(call apt_test_tool,chromium,chromium,the console's browser tests)
gpsd:
	$(call apt_test_tool,gpsd,gpsd,the GPS emulator's gpsd test)

# The suite runs on TEST_JOBS pytest-xdist workers (default: one per core, at
# least 2: most tests wait on processes they start), each in a network
# namespace of its own (tests/conftest.py); `make test TEST_JOBS=0` runs it in
# one process. A test file is one unit of work, so its fixtures run once.
TEST_JOBS ?= $(shell n=$$(nproc 2>/dev/null || echo 2); [ $$n -lt 2 ] && n=2; echo $$n)
TEST_PARALLEL = $(if $(filter 0,$(TEST_JOBS)),-p no:xdist,-n $(TEST_JOBS) --dist loadgroup)
test: build sanitize chromium gpsd lint
	tests/isolated_net.sh $(VPY) -m pytest $(TEST_PARALLEL) $(PYTEST_ARGS)

# The Python's lint and format (ruff, settings in pyproject.toml). `make format`
# rewrites the files; `make lint` only checks, and fails on a difference.
PY_SOURCES := python tests bench
lint: $(VENV_STAMP)
	$(VENV)/bin/ruff check --quiet $(PY_SOURCES)
	$(VENV)/bin/ruff format --quiet --check $(PY_SOURCES)
format: $(VENV_STAMP)
	$(VENV)/bin/ruff check --quiet --fix $(PY_SOURCES)
	$(VENV)/bin/ruff format --quiet $(PY_SOURCES)

# The simulator's validation report (docs/simulator.md): measured against
# reference, PASS/FAIL, non-zero exit on a failure. No LCM.
validate: $(GEN_PY_STAMP)
	$(VENV)/bin/auv-sim-validate

# The tests too long for the suite's budget (each says so when `make test` skips
# it): the backseat team flight (tests/hil/test_hil_wire.py) and the plain
# survey demo over a small area (tests/test_demo.py).
test-slow: build sanitize
	AUV_SLOW_TESTS=1 tests/isolated_net.sh $(VPY) -m pytest -p no:xdist -rs tests/hil/test_hil_wire.py \
	  tests/test_demo.py $(PYTEST_ARGS)

# The suite STRESS_RUNS times in a row with demos running beside it: a test
# that waits on wall time instead of on what it waits for fails here.
STRESS_RUNS ?= 5
stress: build sanitize chromium
	tests/stress.sh $(STRESS_RUNS) $(PYTEST_ARGS)

demo: build
	tests/isolated_net.sh --only-if-needed $(VENV)/bin/auv-demo --out $(BUILD)/demo

LCM_URL ?= udpm://239.255.76.67:7667?ttl=0
spy: $(TYPES_JAR)
	CLASSPATH=$(abspath $(TYPES_JAR)) $(LCM_BIN)/lcm-spy --lcm-url='$(LCM_URL)'

bench: build
	@for b in $(sort $(wildcard bench/*.py)); do echo "== $$b"; \
	  tests/isolated_net.sh --only-if-needed $(VPY) $$b || exit 1; done

clean:
	rm -rf $(BUILD)
distclean: clean
	rm -rf $(VENV)

# `make fuzz` also fuzzes the configuration readers (simulator config and
# scenario) by seeded mutation of the shipped files; a short seeded run is in
# `make test` (tests/fuzz/test_config_fuzz.py).
fuzz: fuzz-config
.PHONY: fuzz-config
fuzz-config: $(VENV_STAMP) $(GEN_PY_STAMP)
	@mkdir -p $(BUILD)/fuzz
	cd $(BUILD)/fuzz && $(abspath $(VPY)) $(abspath tests/fuzz/config_fuzz.py) --seconds $(FUZZ_SECONDS) --seed $$RANDOM
