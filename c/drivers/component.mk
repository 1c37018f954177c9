# The vehicle's device layer (docs/drivers.md): the code every driver shares
# (c/drivers/common: NMEA framing and fields, ...) as libauvdrivers.a, and the
# C unit tests of it and of each driver's parser (tests/drivers/*.c) on the
# shared harness as bin/test_drivers, built in both variants.
DRIVERS_COMMON_SRCS := $(sort $(wildcard c/drivers/common/*.c))
# The protocol layers of the drivers (the DVL's PD0: c/drivers/dvl/pd0*.c) go
# in the same library; their programs (below) are not in it.
DRIVERS_COMMON_SRCS += c/drivers/dvl/pd0_frame.c c/drivers/dvl/pd0_decode.c c/drivers/dvl/pd0_dvl.c
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) $(UNIT_HARNESS_SRCS)

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_COMMON_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS)) $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers

# bin/auv-pd0-dump: a file (or stdin) of PD0 bytes through the framer and the
# decoder, one JSON line per ensemble or refusal (tests/drivers/test_pd0_*.py,
# and a recorded day at sea). bin/pd0_fuzz: the framer and decoder under the
# mutation driver of c/chasm/fuzz (gcc); with clang, `make fuzz` builds a
# libFuzzer binary of the same entry point.
define pd0_rules
$(1)/bin/auv-pd0-dump: $(1)/obj/c/drivers/dvl/pd0_dump.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
$(1)/bin/pd0_fuzz: $(1)/obj/c/drivers/fuzz/fuzz_pd0.o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call pd0_rules,$(v))))
C_PROGRAMS += bin/auv-pd0-dump bin/pd0_fuzz

.PHONY: fuzz-pd0
fuzz: fuzz-pd0
PD0_FUZZ_SRCS := c/drivers/fuzz/fuzz_pd0.c c/drivers/dvl/pd0_frame.c c/drivers/dvl/pd0_decode.c c/drivers/dvl/pd0_dvl.c
ifneq ($(CLANG),)
$(BUILD)/fuzz/pd0_libfuzzer: $(PD0_FUZZ_SRCS) $(GEN_C_STAMP)
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_DEFAULT_SOURCE -g -O1 -Ic -I$(GEN)/c -I$(LCM_INC) -fsanitize=fuzzer,address,undefined $(PD0_FUZZ_SRCS) -o $@ -lm
fuzz-pd0: $(BUILD)/fuzz/pd0_libfuzzer
	@mkdir -p $(BUILD)/fuzz/pd0_corpus && cp tests/drivers/corpus/pd0/* $(BUILD)/fuzz/pd0_corpus/
	$< -max_total_time=$(FUZZ_SECONDS) $(BUILD)/fuzz/pd0_corpus
else
fuzz-pd0: $(BUILD)/san/bin/pd0_fuzz
	$< --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/drivers/corpus/pd0
endif
