# The vehicle's dynamics (docs/simulator.md, "The model"): a shared library
# the simulator loads with ctypes (python/sim/dynamics.py), and its C unit
# tests on the shared harness, built in both variants (the sanitized test
# checks the equations under ASan/UBSan; the library itself is loaded by
# Python, which an ASan library would need LD_PRELOAD for).
DYNAMICS_SRCS := $(sort $(wildcard c/dynamics/*.c))
DYNAMICS_TEST_SRCS := $(sort $(wildcard tests/dynamics/*.c)) $(UNIT_HARNESS_SRCS)

define dynamics_rules
$(1)/lib/libauvdynamics.so: $(patsubst %.c,$(1)/obj/%.o,$(DYNAMICS_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) -shared $$^ -o $$@ -lm
$(1)/bin/test_dynamics: $(patsubst %.c,$(1)/obj/%.o,$(DYNAMICS_TEST_SRCS) $(DYNAMICS_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call dynamics_rules,$(v))))

C_PROGRAMS += lib/libauvdynamics.so bin/test_dynamics

# The validation report runs the dynamics.
validate: $(BUILD)/lib/libauvdynamics.so
