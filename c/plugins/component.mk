# Behavior and test-handler plugins.
#
# Every directory c/plugins/NAME/ (except lib/) is one plugin: its .c files
# become plugins/chasm_NAME.so, which plans load with `use NAME`.
# c/plugins/lib/ holds code shared by plugins (angles, PID, geometry); it is
# linked into each plugin, so a plugin still depends on nothing at run time.
# Unit tests of plugin NAME are tests/plugins/NAME/*.c, linked with libchasm,
# the plugin's own objects, tests/plugins/common/*.c (main) and the shared
# unit-test harness (tests/harness), as bin/test_plugin_NAME.
PLUGIN_DIRS := $(sort $(patsubst c/plugins/%/,%,$(dir $(wildcard c/plugins/*/*.c))))
PLUGIN_NAMES := $(filter-out lib,$(PLUGIN_DIRS))
PLUGIN_LIB_SRCS := $(sort $(wildcard c/plugins/lib/*.c))
PLUGIN_TESTED := $(sort $(filter $(PLUGIN_NAMES),$(patsubst tests/plugins/%/,%,$(dir $(wildcard tests/plugins/*/*.c)))))
PLUGIN_TEST_COMMON := $(sort $(wildcard tests/plugins/common/*.c)) $(UNIT_HARNESS_SRCS) $(PLAN_TEST_SRCS)

define plugin_lib_rules
$(1)/lib/libchasm_plugin_util.a: $(patsubst %.c,$(1)/obj/%.o,$(PLUGIN_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
endef

# LCM types compiled into a plugin: c/plugins/NAME/lcmtypes.list names them,
# one a line (`modem_tx_t`, `#` comments), nested types too. The plugin then
# includes "auv/auv_modem_tx_t.h" and calls auv_modem_tx_t_encode/_decode. It
# still depends on nothing at run time: lcm-gen's files also define publish
# and subscribe, which call liblcm, so they are compiled with one section per
# function and hidden visibility, and the link drops every section the plugin
# does not reach (--gc-sections); the link then fails if any lcm_* or auv_*
# symbol is left undefined (a listed type uses a nested type not listed).
# $(1): a file; $(2): where it is, for the error.
plugin_lcm_types = $(foreach t,$(shell sed -e 's/\#.*//' $(1) 2>/dev/null),$(if $(filter $(t),$(LCM_TYPES)),$(t),$(error $(1): unknown LCM type '$(t)' (no lcmtypes/$(t).lcm))))
PLUGIN_LCM_CFLAGS := -ffunction-sections -fdata-sections -fvisibility=hidden

define plugin_lcm_obj_rules
$(1)/obj/plugin_lcm/%.o: $(GEN)/c/%.c Makefile c/plugins/component.mk
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(CFLAGS_ALL) $$(vflags) $$(GEN_CFLAGS) $$(PLUGIN_LCM_CFLAGS) -c $$< -o $$@
endef

# $(1) variant, $(2) plugin name
define plugin_rules
PLUGIN_LCM_$(2) := $(call plugin_lcm_types,c/plugins/$(2)/lcmtypes.list)
$(1)/plugins/chasm_$(2).so: $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard c/plugins/$(2)/*.c))) $$(patsubst %,$(1)/obj/plugin_lcm/auv_%.o,$$(PLUGIN_LCM_$(2))) $(1)/lib/libchasm_plugin_util.a $(wildcard c/plugins/$(2)/lcmtypes.list)
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) -shared $$(filter %.o %.a,$$^) -o $$@ -lm -Wl,--gc-sections
	@if nm -D --undefined-only $$@ | grep -E ' (lcm_|__?auv_)' >&2; then \
	    echo "$$@: undefined LCM symbols (list nested types in c/plugins/$(2)/lcmtypes.list)" >&2; rm -f $$@; exit 1; fi
endef

define plugin_test_rules
$(1)/bin/test_plugin_$(2): $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard tests/plugins/$(2)/*.c)) $(PLUGIN_TEST_COMMON)) $(patsubst %.c,$(1)/obj/%.o,$(sort $(wildcard c/plugins/$(2)/*.c))) $$(patsubst %,$(1)/obj/plugin_lcm/auv_%.o,$$(PLUGIN_LCM_$(2))) $(1)/lib/libchasm_plugin_util.a $(1)/lib/libchasm.a
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LDLIBS_ALL) -Wl,--gc-sections
endef

$(foreach v,$(VARIANTS),$(eval $(call plugin_lib_rules,$(v))))
$(foreach v,$(VARIANTS),$(eval $(call plugin_lcm_obj_rules,$(v))))
# The same for the single-file test plugins tests/chasm/plugins/NAME.c.
define test_plugin_lcm_rules
$(1)/plugins/chasm_$(2).so: $(patsubst %,$(1)/obj/plugin_lcm/auv_%.o,$(call plugin_lcm_types,tests/chasm/plugins/$(2).lcmtypes.list)) tests/chasm/plugins/$(2).lcmtypes.list
endef
$(foreach v,$(VARIANTS),$(foreach p,$(patsubst tests/chasm/plugins/%.lcmtypes.list,%,$(wildcard tests/chasm/plugins/*.lcmtypes.list)),$(eval $(call test_plugin_lcm_rules,$(v),$(p)))))
$(foreach v,$(VARIANTS),$(foreach p,$(PLUGIN_NAMES),$(eval $(call plugin_rules,$(v),$(p)))))
$(foreach v,$(VARIANTS),$(foreach p,$(PLUGIN_TESTED),$(eval $(call plugin_test_rules,$(v),$(p)))))

C_PROGRAMS += $(foreach p,$(PLUGIN_NAMES),plugins/chasm_$(p).so) $(foreach p,$(PLUGIN_TESTED),bin/test_plugin_$(p))
C_LIBS += lib/libchasm_plugin_util.a
