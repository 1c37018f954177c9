# The LCM sender thread (docs/simulator.md, "Performance"), the channel filter
# and the own-socket reader: a shared library Python loads with ctypes, and
# the sender's C test, built in both variants (the sanitized test checks the
# queue and the thread under ASan/UBSan).
SENDER_SRCS := $(sort $(wildcard c/sender/*.c)) c/common/lcm_chanfilter.c c/common/chanfilter_compile.c c/common/lcm_socket.c c/common/lcm_udpm_reader.c c/common/lockstep_board.c
SENDER_TEST_SRCS := $(sort $(wildcard tests/sender/*.c))

define sender_rules
$(1)/lib/libauvlcm_sender.so: $(patsubst %.c,$(1)/obj/%.o,$(SENDER_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) -shared $$^ -o $$@ $$(LCM_LDLIBS) -lpthread
$(1)/bin/test_lcm_sender: $(patsubst %.c,$(1)/obj/%.o,$(SENDER_TEST_SRCS) $(SENDER_SRCS))
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ $$(LCM_LDLIBS) $$(LDLIBS_ALL)
endef
$(foreach v,$(VARIANTS),$(eval $(call sender_rules,$(v))))

C_PROGRAMS += lib/libauvlcm_sender.so bin/test_lcm_sender
