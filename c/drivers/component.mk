# The vehicle's device layer (docs/drivers.md): the code every driver shares
# (c/drivers/common: NMEA framing and fields, ...) as libauvdrivers.a, and the
# C unit tests of it and of each driver's parser (tests/drivers/*.c) on the
# shared harness as bin/test_drivers, built in both variants.
DRIVERS_COMMON_SRCS := $(sort $(wildcard c/drivers/common/*.c))
# The Micro-Modem's protocol layer and bridge (no I/O: unit-tested here).
DRIVERS_COMMON_SRCS += $(sort $(wildcard c/drivers/modem/mm_*.c))
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) $(UNIT_HARNESS_SRCS)

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_COMMON_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS)) $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
# The Micro-Modem bridge on stdin/stdout (tests/drivers/test_micromodem.py puts
# it face to face with the simulator's emulator), and its fuzz target.
$(1)/bin/mm_cli: $(1)/obj/c/drivers/tools/mm_cli.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
$(1)/bin/mm_fuzz: $(1)/obj/c/drivers/fuzz/fuzz_mm.o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers bin/mm_cli bin/mm_fuzz

# `make fuzz` also fuzzes the Micro-Modem parser and bridge (FUZZ_SECONDS, the
# hostile corpus as seeds): libFuzzer with clang, else the self-written driver.
.PHONY: fuzz-mm
fuzz: fuzz-mm
ifneq ($(CLANG),)
$(BUILD)/fuzz/mm_libfuzzer: $(DRIVERS_COMMON_SRCS) c/drivers/fuzz/fuzz_mm.c
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_DEFAULT_SOURCE -g -O1 -Ic -fsanitize=fuzzer,address,undefined $^ -o $@ -lm
fuzz-mm: $(BUILD)/fuzz/mm_libfuzzer
	@mkdir -p $(BUILD)/fuzz/mm_corpus && cp tests/drivers/corpus/mm/* $(BUILD)/fuzz/mm_corpus/
	$< -max_total_time=$(FUZZ_SECONDS) $(BUILD)/fuzz/mm_corpus
else
fuzz-mm: $(BUILD)/san/bin/mm_fuzz
	$< --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/drivers/corpus/mm
endif
