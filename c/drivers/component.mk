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
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers
