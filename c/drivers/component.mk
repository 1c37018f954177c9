# The vehicle's device layer (docs/drivers.md).
#  - libauvdrivers.a: the code every driver shares (c/drivers/common: the
#    framework - port, options, loop, status, drop reasons, raw recording - and
#    NMEA framing and fields);
#  - bin/auv-<device> for each folder c/drivers/<device>/ (every folder but
#    common, replay and fuzz): its <device>_main.c and its protocol (the other
#    .c files of the folder). A new driver is a new folder: nothing to add here;
#  - bin/auv-driver-replay and bin/drivers_fuzz: every device's protocol
#    linked in (each registers itself with DRV_REGISTER);
#  - bin/test_drivers: the C unit tests (tests/drivers/*.c) on the shared
#    harness, with every protocol linked in.
# All in both variants.
DRIVERS_COMMON_SRCS := $(sort $(wildcard c/drivers/common/*.c))
DRIVERS_DEVICES := $(filter-out common replay fuzz,$(notdir $(patsubst %/,%,$(sort $(dir $(wildcard c/drivers/*/*.c))))))
drivers_protocol_srcs = $(filter-out %_main.c,$(wildcard c/drivers/$(1)/*.c))
DRIVERS_PROTOCOL_SRCS := $(foreach d,$(DRIVERS_DEVICES),$(call drivers_protocol_srcs,$(d)))
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) $(UNIT_HARNESS_SRCS)
DRIVERS_LIBS = $(1)/lib/libauvdrivers.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_COMMON_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS) $(DRIVERS_PROTOCOL_SRCS)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/auv-driver-replay: $(patsubst %.c,$(1)/obj/%.o,$(wildcard c/drivers/replay/*.c) $(DRIVERS_PROTOCOL_SRCS)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/drivers_fuzz: $(patsubst %.c,$(1)/obj/%.o,c/drivers/fuzz/fuzz_protocols.c c/chasm/fuzz/fuzz_driver.c $(DRIVERS_PROTOCOL_SRCS)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

# One program per device folder, in each variant.
define driver_program_rules
$(1)/bin/auv-$(2): $(patsubst %.c,$(1)/obj/%.o,$(wildcard c/drivers/$(2)/*.c)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(foreach d,$(DRIVERS_DEVICES),$(eval $(call driver_program_rules,$(v),$(d)))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers bin/auv-driver-replay bin/drivers_fuzz $(addprefix bin/auv-,$(DRIVERS_DEVICES))

# `make fuzz`: every driver's protocol (NMEA framing and the GPS sentences
# included) under the mutation fuzzer, from the hostile corpora of
# tests/drivers/corpus/, FUZZ_SECONDS; a crash aborts (ASan+UBSan build).
.PHONY: fuzz-drivers
fuzz: fuzz-drivers
fuzz-drivers: $(BUILD)/san/bin/drivers_fuzz
	$< --seconds $(FUZZ_SECONDS) --seed $$RANDOM --no-dict tests/drivers/corpus
