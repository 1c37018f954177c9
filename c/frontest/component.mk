# The on-board front estimator (C++17 + Eigen, docs/sampling.md, "The on-board
# front estimator"): the model, the Levenberg-Marquardt fit and the sample
# intake as a library, the auv-front-estimate process, and their unit tests
# (tests/frontest/unit, bin/frontest_unit_tests).
FRONTEST_MAIN_SRCS := c/frontest/auv_front_estimate_main.cpp
FRONTEST_LIB_SRCS := $(filter-out $(FRONTEST_MAIN_SRCS),$(sort $(wildcard c/frontest/*.cpp)))
FRONTEST_UNIT_SRCS := $(sort $(wildcard tests/frontest/unit/*.cpp))

define frontest_rules
$(1)/lib/libauvfrontest.a: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/auv-front-estimate: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_MAIN_SRCS)) $(1)/lib/libauvfrontest.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/frontest_unit_tests: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_UNIT_SRCS)) $(patsubst %.c,$(1)/obj/%.o,$(UNIT_HARNESS_SRCS)) $(1)/lib/libauvfrontest.a $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call frontest_rules,$(v))))

C_PROGRAMS += bin/auv-front-estimate $(if $(FRONTEST_UNIT_SRCS),bin/frontest_unit_tests)
C_LIBS += lib/libauvfrontest.a
