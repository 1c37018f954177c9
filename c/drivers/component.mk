# The vehicle's device layer (docs/drivers.md): the code every driver shares
# (c/drivers/common: NMEA framing and fields, ...) and the fins-and-thruster
# protocol and channel table (c/drivers/servo) as libauvdrivers.a, and the
# C unit tests of it and of each driver's parser (tests/drivers/*.c) on the
# shared harness as bin/test_drivers, built in both variants.
DRIVERS_COMMON_SRCS := $(sort $(wildcard c/drivers/common/*.c))
DRIVERS_SERVO_SRCS := c/drivers/servo/maestro.c c/drivers/servo/actuator_map.c c/drivers/servo/am_config.c
DRIVERS_LIB_SRCS := $(DRIVERS_COMMON_SRCS) $(DRIVERS_SERVO_SRCS)
# the fuzz target's one-input check runs on the hostile corpus in the tests too
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) c/drivers/fuzz/fuzz_maestro.c $(UNIT_HARNESS_SRCS)

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS)) $(1)/lib/libauvdrivers.a $(1)/lib/libauvcommon.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
$(1)/bin/auv-maestro-encode: $(1)/obj/c/drivers/servo/maestro_encode_main.o $(1)/lib/libauvdrivers.a $(1)/lib/libauvcommon.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
$(1)/bin/maestro_fuzz: $(1)/obj/c/drivers/fuzz/fuzz_maestro.o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libauvdrivers.a $(1)/lib/libauvcommon.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers bin/auv-maestro-encode bin/maestro_fuzz

# Long fuzz run of the Maestro's reply decoder and channel-table reader
# (c/drivers/fuzz/fuzz_maestro.c), seeded with tests/drivers/corpus/maestro;
# FUZZ_SECONDS and CLANG as in c/chasm/component.mk.
.PHONY: fuzz-maestro
fuzz: fuzz-maestro
ifneq ($(CLANG),)
$(BUILD)/fuzz/maestro_libfuzzer: c/drivers/fuzz/fuzz_maestro.c $(DRIVERS_SERVO_SRCS) c/common/time_policy.c
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_DEFAULT_SOURCE -g -O1 -Ic -fsanitize=fuzzer,address,undefined $^ -o $@ -lm
fuzz-maestro: $(BUILD)/fuzz/maestro_libfuzzer
	@mkdir -p $(BUILD)/fuzz/maestro_corpus && cp tests/drivers/corpus/maestro/* $(BUILD)/fuzz/maestro_corpus/
	$< -max_total_time=$(FUZZ_SECONDS) $(BUILD)/fuzz/maestro_corpus
else
fuzz-maestro: $(BUILD)/san/bin/maestro_fuzz
	$< --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/drivers/corpus/maestro
endif
