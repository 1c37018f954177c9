# auv-recorder (docs/tools.md, "Recorder"): the LCM recorder the launcher
# uses, built in both variants. It takes part in lockstep with the managers'
# own participant code (c/managers/mgr_lockstep.c), linked, not copied.
RECORDER_SRCS := $(sort $(wildcard c/recorder/*.c)) c/managers/mgr_lockstep.c

define recorder_rules
$(1)/bin/auv-recorder: $(patsubst %.c,$(1)/obj/%.o,$(RECORDER_SRCS)) $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call recorder_rules,$(v))))

C_PROGRAMS += bin/auv-recorder
