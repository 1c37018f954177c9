# Manager executables: LCM glue around libchasm.
MANAGER_SRCS := $(sort $(wildcard c/managers/*.c))

define manager_rules
$(1)/bin/chasm-manager: $(patsubst %.c,$(1)/obj/%.o,$(MANAGER_SRCS)) $(1)/lib/libchasm.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call manager_rules,$(v))))

C_PROGRAMS += bin/chasm-manager
