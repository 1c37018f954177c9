# The pilot's control law as a shared library, build/lib/libauvpilot.so,
# which the simulator's validation loads with ctypes (python/sim/pilot.py)
# to fly the vehicle in-process. Its loops are the pilot plugin's own source
# (c/plugins/pilot/pilot_loops.c and the plugin lib's PID, limits and
# angles), compiled once more here: one law, two linkings. Both variants, as
# c/dynamics does (the sanitized one for a C caller; Python loads the normal
# one, an ASan library would need LD_PRELOAD).
PILOTLIB_SRCS := $(sort $(wildcard c/pilotlib/*.c)) c/plugins/pilot/pilot_loops.c \
    c/plugins/lib/pu_pid.c c/plugins/lib/pu_limit.c c/plugins/lib/pu_angle.c

define pilotlib_rules
$(1)/lib/libauvpilot.so: $(patsubst %.c,$(1)/obj/%.o,$(PILOTLIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) -shared $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call pilotlib_rules,$(v))))

C_PROGRAMS += lib/libauvpilot.so

# The validation report flies the pilot through it.
validate: $(BUILD)/lib/libauvpilot.so
