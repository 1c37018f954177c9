# The on-board front estimator (C++17 + Eigen, docs/sampling.md, "The on-board
# front estimator"): the model, the Levenberg-Marquardt fit and the sample
# intake as a library, the auv-front-estimate process, and their unit tests
# (tests/frontest/unit, bin/frontest_unit_tests). The team link's codec
# (c/teamlink, generated from c/plugins/team/team_link.schema) is linked in for
# the front summaries teammates send (front_summary.cpp).
FRONTEST_MAIN_SRCS := c/frontest/auv_front_estimate_main.cpp
FRONTEST_LIB_SRCS := $(filter-out $(FRONTEST_MAIN_SRCS),$(sort $(wildcard c/frontest/*.cpp)))
FRONTEST_UNIT_SRCS := $(sort $(wildcard tests/frontest/unit/*.cpp))

# The generated codec header is C, under $(GEN); the objects that include it wait for it
# (the stamp by its path: c/teamlink/component.mk is read after this file).
CXXFLAGS_ALL += -I$(GEN)
FRONTEST_CODEC = $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o $(1)/obj/c/teamlink/team_front.o

define frontest_rules
$(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_LIB_SRCS) $(FRONTEST_MAIN_SRCS) $(FRONTEST_UNIT_SRCS)): | $(GEN)/team/codec.stamp
$(1)/lib/libauvfrontest.a: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_LIB_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(AR) rcs $$@ $$^
$(1)/bin/auv-front-estimate: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_MAIN_SRCS)) $(1)/lib/libauvfrontest.a $(call FRONTEST_CODEC,$(1)) $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
$(1)/bin/frontest_unit_tests: $(patsubst %.cpp,$(1)/obj/%.o,$(FRONTEST_UNIT_SRCS)) $(patsubst %.c,$(1)/obj/%.o,$(UNIT_HARNESS_SRCS)) $(1)/lib/libauvfrontest.a $(call FRONTEST_CODEC,$(1)) $(1)/lib/libauvcommon.a $(1)/lib/libauvtypes.a
	@mkdir -p $$(@D)
	$$(Q)$$(CXX) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call frontest_rules,$(v))))

C_PROGRAMS += bin/auv-front-estimate $(if $(FRONTEST_UNIT_SRCS),bin/frontest_unit_tests)
C_LIBS += lib/libauvfrontest.a
