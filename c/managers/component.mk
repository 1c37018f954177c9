# Manager executables: LCM glue around libchasm.
MANAGER_SRCS := $(sort $(wildcard c/managers/*.c))

define manager_rules
$(1)/bin/chasm-manager: $(patsubst %.c,$(1)/obj/%.o,$(MANAGER_SRCS)) $(1)/lib/libchasm.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call manager_rules,$(v))))

C_PROGRAMS += bin/chasm-manager

# Fuzz target of the binding-file parser: mgr_bindings.c against a fixed plan.
BIND_FUZZ_OBJS = $(1)/obj/c/managers/fuzz/fuzz_bindings.o $(1)/obj/c/managers/mgr_bindings.o $(1)/obj/c/managers/mgr_bind_parse.o $(1)/obj/c/managers/mgr_bind_files.o $(1)/obj/c/managers/mgr_errors.o $(1)/obj/c/managers/mgr_held.o $(1)/obj/c/managers/mgr_inputs.o
define bind_fuzz_rules
$(1)/bin/chasm_bind_fuzz: $(call BIND_FUZZ_OBJS,$(1)) $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libchasm.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call bind_fuzz_rules,$(v))))
C_PROGRAMS += bin/chasm_bind_fuzz

.PHONY: fuzz-bindings
fuzz: fuzz-bindings
ifneq ($(CLANG),)
$(BUILD)/fuzz/bind_libfuzzer: c/managers/fuzz/fuzz_bindings.c c/managers/mgr_bindings.c c/managers/mgr_bind_parse.c c/managers/mgr_bind_files.c c/managers/mgr_errors.c c/managers/mgr_held.c c/managers/mgr_inputs.c $(wildcard c/common/*.c) $(GEN_C_SRCS) $(CHASM_LIB_SRCS)
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_DEFAULT_SOURCE -g -O1 -Ic -I$(GEN)/c -I$(LCM_INC) -Wno-cast-function-type -fsanitize=fuzzer,address,undefined -fno-sanitize=nonnull-attribute $^ -o $@ $(LCM_LDLIBS) -lm -ldl -lpthread -lcrypto
fuzz-bindings: $(BUILD)/fuzz/bind_libfuzzer
	@mkdir -p $(BUILD)/fuzz/bind_corpus && cp tests/managers/bind_corpus/* $(BUILD)/fuzz/bind_corpus/
	$< -max_total_time=$(FUZZ_SECONDS) $(BUILD)/fuzz/bind_corpus
else
fuzz-bindings: $(BUILD)/san/bin/chasm_bind_fuzz
	$< --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/managers/bind_corpus
endif
