# libchasm, the chasm tool, its tests, fuzz target and benchmark.
# Included by the top Makefile; defines rules for each build variant.

comma := ,
CHASM_LIB_SRCS := $(sort $(wildcard c/chasm/cm_*.c))
CHASM_TOOL_SRCS := $(sort $(wildcard c/chasm/tool/*.c))
CHASM_UNIT_SRCS := $(sort $(wildcard tests/chasm/unit/*.c)) $(UNIT_HARNESS_SRCS) $(UNIT_ALLOC_SRCS) $(PLAN_TEST_SRCS)
CHASM_TEST_PLUGINS := $(patsubst tests/chasm/plugins/%.c,plugins/chasm_%.so,$(sort $(wildcard tests/chasm/plugins/*.c)))

define chasm_rules
$(1)/lib/libchasm.a: $(patsubst %.c,$(1)/obj/%.o,$(CHASM_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(AR) rcs $$@ $$^
$(1)/bin/chasm: $(patsubst %.c,$(1)/obj/%.o,$(CHASM_TOOL_SRCS)) $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL)
# The unit tests wrap malloc & co. to prove chasm_step() never allocates.
$(1)/bin/chasm_unit_tests: $(patsubst %.c,$(1)/obj/%.o,$(CHASM_UNIT_SRCS)) $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) $$^ -o $$@ -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc $$(LDLIBS_ALL)
$(1)/bin/chasm_fuzz: $(1)/obj/c/chasm/fuzz/fuzz_loader.o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL)
$(1)/bin/chasm_fuzz_plugin: $(1)/obj/c/chasm/fuzz/fuzz_plugin_file.o $(1)/obj/c/chasm/fuzz/fuzz_driver.o $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL)
$(1)/bin/chasm_bench: $(1)/obj/bench/chasm_bench.o $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL)
# Test plugins: one source each (good, v2, broken, wrong ABI, ...).
# A test plugin with a NAME.lcmtypes.list gets those LCM types compiled in,
# like c/plugins/NAME/lcmtypes.list (c/plugins/component.mk).
$(1)/plugins/chasm_%.so: $(1)/obj/tests/chasm/plugins/%.o
	@mkdir -p $$(@D)
	$$(CC) $$(vflags) -shared $$(filter %.o,$$^) -o $$@ $$(if $$(findstring /plugin_lcm/,$$^),-Wl$$(comma)--gc-sections)
	@if nm -D --undefined-only $$@ | grep -E ' (lcm_|__?auv_)' >&2; then \
	    echo "$$@: undefined LCM symbols (list nested types in its .lcmtypes.list)" >&2; rm -f $$@; exit 1; fi
endef
$(foreach v,$(VARIANTS),$(eval $(call chasm_rules,$(v))))

C_PROGRAMS += bin/chasm bin/chasm_unit_tests bin/chasm_fuzz bin/chasm_fuzz_plugin bin/chasm_bench $(CHASM_TEST_PLUGINS)
C_LIBS += lib/libchasm.a

# Long fuzz runs: the Loader here, the binding-file parser in
# c/managers/component.mk (`make fuzz` runs both, FUZZ_SECONDS each). With
# clang, real libFuzzer binaries; otherwise the self-written mutation driver
# (built with ASan+UBSan). FUZZ_SECONDS=600.
FUZZ_SECONDS ?= 600
CLANG := $(shell command -v clang 2>/dev/null)
.PHONY: fuzz fuzz-loader
fuzz: fuzz-loader
ifneq ($(CLANG),)
$(BUILD)/fuzz/chasm_libfuzzer: $(CHASM_LIB_SRCS) c/chasm/fuzz/fuzz_loader.c
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_POSIX_C_SOURCE=200809L -g -O1 -Ic -fsanitize=fuzzer,address,undefined $^ -o $@ -lm -ldl
fuzz-loader: $(BUILD)/fuzz/chasm_libfuzzer
	@mkdir -p $(BUILD)/fuzz/corpus && cp tests/chasm/fuzz_corpus/* $(BUILD)/fuzz/corpus/
	$< -max_total_time=$(FUZZ_SECONDS) -dict=c/chasm/fuzz/chasm.dict $(BUILD)/fuzz/corpus
else
fuzz-loader: $(BUILD)/san/bin/chasm_fuzz
	$< --seconds $(FUZZ_SECONDS) --seed $$RANDOM tests/chasm/fuzz_corpus
endif

# Long fuzz run of the plugin loader's file check (cm_elf_check; every input it
# accepts goes through the whole open: probe process, dlopen), seeded with the
# sanitized build's plugins but those whose constructor crashes, exits or hangs
# on purpose (each such input would cost a probe). FUZZ_SECONDS too.
.PHONY: fuzz-plugin-file
fuzz: fuzz-plugin-file
PLUGIN_SEEDS = $$(ls $(BUILD)/san/plugins/*.so | grep -v '/chasm_test_ctor_')
ifneq ($(CLANG),)
$(BUILD)/fuzz/chasm_plugin_libfuzzer: $(CHASM_LIB_SRCS) c/chasm/fuzz/fuzz_plugin_file.c
	@mkdir -p $(@D)
	$(CLANG) -std=c11 -D_POSIX_C_SOURCE=200809L -g -O1 -Ic -fsanitize=fuzzer,address,undefined $^ -o $@ -lm -ldl
fuzz-plugin-file: $(BUILD)/fuzz/chasm_plugin_libfuzzer $(addprefix $(BUILD)/san/,$(CHASM_TEST_PLUGINS))
	@mkdir -p $(BUILD)/fuzz/plugin_corpus && cp $(PLUGIN_SEEDS) $(BUILD)/fuzz/plugin_corpus/
	$< -max_total_time=$(FUZZ_SECONDS) $(BUILD)/fuzz/plugin_corpus
else
fuzz-plugin-file: $(BUILD)/san/bin/chasm_fuzz_plugin $(addprefix $(BUILD)/san/,$(CHASM_TEST_PLUGINS))
	$< --no-dict --seconds $(FUZZ_SECONDS) --seed $$RANDOM $(PLUGIN_SEEDS)
endif
