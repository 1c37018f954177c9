# The vehicle's device layer (docs/drivers.md), all in both variants:
#  - libauvdrivers.a: what every driver shares (c/drivers/common: the framework
#    - port, options, loop, status, drop reasons, raw recording - and NMEA
#    framing and fields);
#  - protocol code: every .c of a device folder c/drivers/<device>/ but its
#    <device>_main.c (each protocol registers itself with DRV_REGISTER); it is
#    linked into every program below, so the replay, the fuzzers and the unit
#    tests decode exactly as the drivers do;
#  - bin/auv-<device> for each device folder with a <device>_main.c: a new
#    driver is a new folder, nothing to add here;
#  - bin/auv-driver-replay (c/drivers/replay), bin/NAME for each tool
#    c/drivers/tools/NAME.c (underscores become dashes: auv_pd0_dump.c is auv-pd0-dump), bin/drivers_fuzz_NAME for each fuzz target
#    c/drivers/fuzz/fuzz_NAME.c, and bin/test_drivers: the C unit tests
#    (tests/drivers/*.c, each file registering its own list) on the shared harness.
DRIVERS_COMMON_SRCS := $(sort $(wildcard c/drivers/common/*.c))
# (the servo folder's protocol and table code are protocol sources below, as every device's)
DRIVERS_DEVICES := $(filter-out common replay fuzz tools,$(notdir $(patsubst %/,%,$(sort $(dir $(wildcard c/drivers/*/*.c))))))
DRIVERS_PROTOCOL_SRCS := $(sort $(foreach d,$(DRIVERS_DEVICES),$(filter-out %/$(d)_main.c,$(wildcard c/drivers/$(d)/*.c))))
# Drivers kept outside c/drivers because they are more than a device: a folder
# c/<name>/ with a <name>_main.c, built as bin/auv-<name> on this framework and
# linked into the replay, the fuzzers and bin/test_drivers like every protocol
# (c/frontseat: auv-frontseat, standing where the pilot stands on a commercial
# vehicle, docs/frontseat.md).
DRIVERS_OUTSIDE := frontseat
DRIVERS_PROTOCOL_SRCS += $(sort $(foreach d,$(DRIVERS_OUTSIDE),$(filter-out %/$(d)_main.c,$(wildcard c/$(d)/*.c))))
DRIVERS_PROGRAMS := $(sort $(foreach d,$(DRIVERS_DEVICES),$(if $(wildcard c/drivers/$(d)/$(d)_main.c),$(d))))
DRIVERS_TOOLS := $(sort $(patsubst c/drivers/tools/%.c,%,$(wildcard c/drivers/tools/*.c)))
DRIVERS_FUZZ := $(sort $(patsubst c/drivers/fuzz/fuzz_%.c,%,$(wildcard c/drivers/fuzz/fuzz_*.c)))
# (the Maestro's corpus test calls its fuzz target's maestro_fuzz_one())
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) c/drivers/fuzz/fuzz_maestro.c $(UNIT_HARNESS_SRCS)
DRIVERS_LIBS = $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_PROTOCOL_SRCS)) $(1)/lib/libauvdrivers.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
# the radio gateway reads the shore's team-link `command` (c/teamlink's generated
# codec): every program that links the protocols links the codec, and the
# radio's objects wait for it to be generated
DRIVERS_LIBS += $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o
$(foreach v,$(VARIANTS),$(patsubst %.c,$(v)/obj/%.o,$(wildcard c/drivers/radio/*.c) tests/drivers/test_radio.c)): | $(GEN)/team/codec.stamp
DRIVERS_LINK = $$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_COMMON_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$(DRIVERS_LINK)
$(1)/bin/auv-driver-replay: $(patsubst %.c,$(1)/obj/%.o,$(wildcard c/drivers/replay/*.c)) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$(DRIVERS_LINK)
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

# $(1): variant; $(2): the program's name; $(3): its own source
define drivers_program_rule
$(1)/bin/$(2): $(1)/obj/$(3:.c=.o) $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$(DRIVERS_LINK)
endef
$(foreach v,$(VARIANTS),$(foreach d,$(DRIVERS_PROGRAMS),$(eval $(call drivers_program_rule,$(v),auv-$(d),c/drivers/$(d)/$(d)_main.c))))
$(foreach v,$(VARIANTS),$(foreach d,$(DRIVERS_OUTSIDE),$(eval $(call drivers_program_rule,$(v),auv-$(d),c/$(d)/$(d)_main.c))))
$(foreach v,$(VARIANTS),$(foreach t,$(DRIVERS_TOOLS),$(eval $(call drivers_program_rule,$(v),$(subst _,-,$(t)),c/drivers/tools/$(t).c))))
# the fuzz targets run on the project's mutation driver (no libFuzzer needed)
define drivers_fuzz_rule
$(1)/bin/drivers_fuzz_$(2): $(1)/obj/c/drivers/fuzz/fuzz_$(2).o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(call DRIVERS_LIBS,$(1))
	@mkdir -p $$(@D)
	$(DRIVERS_LINK)
endef
$(foreach v,$(VARIANTS),$(foreach f,$(DRIVERS_FUZZ),$(eval $(call drivers_fuzz_rule,$(v),$(f)))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers bin/auv-driver-replay $(addprefix bin/auv-,$(DRIVERS_PROGRAMS) $(DRIVERS_OUTSIDE)) $(addprefix bin/,$(subst _,-,$(DRIVERS_TOOLS)))
C_PROGRAMS += $(addprefix bin/drivers_fuzz_,$(DRIVERS_FUZZ))

# `make fuzz`: each fuzz target over its hostile corpus tests/drivers/corpus/NAME
# (`protocols`, every registered protocol at once, over all of them) for
# FUZZ_SECONDS; a crash aborts (ASan+UBSan build). `make test` runs each briefly
# (tests/drivers/test_driver_fuzz.py).
drivers_corpus = tests/drivers/corpus$(if $(filter protocols,$(1)),,/$(1))
.PHONY: fuzz-drivers
fuzz: fuzz-drivers
fuzz-drivers: $(addprefix $(BUILD)/san/bin/drivers_fuzz_,$(DRIVERS_FUZZ))
	@set -e; $(foreach f,$(DRIVERS_FUZZ),echo "fuzz drivers: $(f) ($(FUZZ_SECONDS) s)"; \
	  $(BUILD)/san/bin/drivers_fuzz_$(f) --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM $(call drivers_corpus,$(f));)
