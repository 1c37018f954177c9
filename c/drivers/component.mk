# The vehicle's device layer (docs/drivers.md): the code every driver shares
# (c/drivers/common: NMEA framing and fields, ...) and each device's protocol
# code (c/drivers/<device>/*.c but its *_main.c; c/drivers/tools holds test
# programs, c/drivers/fuzz the fuzz targets) as libauvdrivers.a, and the C
# unit tests of them (tests/drivers/*.c) on the shared harness as
# bin/test_drivers, built in both variants.
DRIVERS_COMMON_SRCS := $(sort $(filter-out %_main.c c/drivers/tools/% c/drivers/fuzz/%,$(wildcard c/drivers/*/*.c)))
DRIVERS_TEST_SRCS := $(sort $(wildcard tests/drivers/*.c)) $(UNIT_HARNESS_SRCS)

define drivers_rules
$(1)/lib/libauvdrivers.a: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_COMMON_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/test_drivers: $(patsubst %.c,$(1)/obj/%.o,$(DRIVERS_TEST_SRCS)) $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
# The Micro-Modem bridge on stdin/stdout (tests/drivers/test_micromodem.py puts
# it face to face with the simulator's emulator).
$(1)/bin/mm_cli: $(1)/obj/c/drivers/tools/mm_cli.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call drivers_rules,$(v))))

C_LIBS += lib/libauvdrivers.a
C_PROGRAMS += bin/test_drivers bin/mm_cli

# Fuzz targets: each c/drivers/fuzz/fuzz_NAME.c is an LLVMFuzzerTestOneInput over
# one protocol, built as bin/drivers_fuzz_NAME on the project's mutation driver
# (c/chasm/fuzz/fuzz_driver.c) in both variants; tests/drivers/corpus/NAME/ is
# its hostile corpus, which tests/drivers/test_driver_fuzz.py replays and
# mutates briefly in both builds, and `make fuzz` for FUZZ_SECONDS each.
DRIVERS_FUZZ := $(sort $(patsubst c/drivers/fuzz/fuzz_%.c,%,$(wildcard c/drivers/fuzz/fuzz_*.c)))

define drivers_fuzz_rule
$(1)/bin/drivers_fuzz_$(2): $(1)/obj/c/drivers/fuzz/fuzz_$(2).o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libauvdrivers.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(foreach f,$(DRIVERS_FUZZ),$(eval $(call drivers_fuzz_rule,$(v),$(f)))))

C_PROGRAMS += $(addprefix bin/drivers_fuzz_,$(DRIVERS_FUZZ))

.PHONY: fuzz-drivers
fuzz: fuzz-drivers
fuzz-drivers: $(addprefix $(BUILD)/san/bin/drivers_fuzz_,$(DRIVERS_FUZZ))
	@for f in $(DRIVERS_FUZZ); do \
	  echo "fuzz drivers: $$f ($(FUZZ_SECONDS) s)"; \
	  $(BUILD)/san/bin/drivers_fuzz_$$f --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/drivers/corpus/$$f || exit 1; \
	done
