# Onboard navigation (C++17 + Eigen): the EKF library, the auv-nav process,
# the log replay driver and the filter's unit tests. docs/navigation.md.
# auv-nav takes part in lockstep with the managers' participant code
# (c/managers/mgr_lockstep.c), linked, not copied.
NAV_NODE_SRCS := c/nav/nav_node.cpp c/nav/auv_nav_main.cpp
NAV_REPLAY_SRCS := c/nav/replay_eval.cpp c/nav/nav_replay_main.cpp
NAV_LIB_SRCS := $(filter-out $(NAV_NODE_SRCS) $(NAV_REPLAY_SRCS),$(sort $(wildcard c/nav/*.cpp)))
NAV_UNIT_SRCS := $(sort $(wildcard tests/nav/unit/*.cpp))

define nav_rules
$(1)/lib/libauvnav.a: $(patsubst %.cpp,$(1)/obj/%.o,$(NAV_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/auv-nav: $(patsubst %.cpp,$(1)/obj/%.o,$(NAV_NODE_SRCS)) $(1)/obj/c/managers/mgr_lockstep.o $(1)/lib/libauvnav.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/auv-nav-replay: $(patsubst %.cpp,$(1)/obj/%.o,$(NAV_REPLAY_SRCS)) $(1)/lib/libauvnav.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
# The unit tests count allocations (operator new and, wrapped, malloc) to
# prove an update allocates nothing; the harness is C (tests/harness).
$(1)/bin/nav_unit_tests: $(patsubst %.cpp,$(1)/obj/%.o,$(NAV_UNIT_SRCS)) $(patsubst %.c,$(1)/obj/%.o,$(UNIT_HARNESS_SRCS) $(UNIT_ALLOC_SRCS)) $(1)/lib/libauvnav.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call nav_rules,$(v))))

C_PROGRAMS += bin/auv-nav bin/auv-nav-replay $(if $(NAV_UNIT_SRCS),bin/nav_unit_tests)
C_LIBS += lib/libauvnav.a
