# Behavior and test-handler plugins.
#
# Every directory c/plugins/NAME/ (except lib/) is one plugin: its .c files
# become plugins/chasm_NAME.so, which plans load with `use NAME`.
# c/plugins/lib/ holds code shared by plugins (angles, PID, geometry); it is
# linked into each plugin, so a plugin still depends on nothing at run time.
# Unit tests of plugin NAME are tests/plugins/NAME/*.c, linked with libchasm,
# the plugin's own objects and the shared test harness tests/plugins/common/*.c,
# as bin/test_plugin_NAME.
PLUGIN_DIRS := $(sort $(patsubst c/plugins/%/,%,$(dir $(wildcard c/plugins/*/*.c))))
PLUGIN_NAMES := $(filter-out lib,$(PLUGIN_DIRS))
PLUGIN_LIB_SRCS := $(sort $(wildcard c/plugins/lib/*.c))
PLUGIN_TESTED := $(sort $(filter $(PLUGIN_NAMES),$(patsubst tests/plugins/%/,%,$(dir $(wildcard tests/plugins/*/*.c)))))
PLUGIN_TEST_COMMON := $(sort $(wildcard tests/plugins/common/*.c))

define plugin_lib_rules
$(1)/lib/libchasm_plugin_util.a: $(patsubst %.c,$(1)/obj/%.o,$(PLUGIN_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
endef

# $(1) variant, $(2) plugin name
define plugin_rules
$(1)/plugins/chasm_$(2).so: $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard c/plugins/$(2)/*.c))) $(1)/lib/libchasm_plugin_util.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) -shared $$^ -o $$@ -lm
endef

define plugin_test_rules
$(1)/bin/test_plugin_$(2): $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard tests/plugins/$(2)/*.c)) $(PLUGIN_TEST_COMMON)) $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard c/plugins/$(2)/*.c))) $(1)/lib/libchasm_plugin_util.a $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL)
endef

$(foreach v,$(VARIANTS),$(eval $(call plugin_lib_rules,$(v))))
$(foreach v,$(VARIANTS),$(foreach p,$(PLUGIN_NAMES),$(eval $(call plugin_rules,$(v),$(p)))))
$(foreach v,$(VARIANTS),$(foreach p,$(PLUGIN_TESTED),$(eval $(call plugin_test_rules,$(v),$(p)))))

C_PROGRAMS += $(foreach p,$(PLUGIN_NAMES),plugins/chasm_$(p).so) $(foreach p,$(PLUGIN_TESTED),bin/test_plugin_$(p))
C_LIBS += lib/libchasm_plugin_util.a
