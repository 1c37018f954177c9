# The team-link codec (docs/modem.md, "The team-link codec").
#
# c/plugins/team/team_link.schema -> python/tools/codegen/gen_team_codec.py ->
# build/gen/team/team_codec.h/.c. Code includes "team/team_codec.h" (-I$(GEN)).
# The generated codec, the bit writer/reader (c/teamlink/team_bits.c) and the
# front summary's maker (team_front.c, shared with auv-front-estimate) are
# compiled into the team plugin (plugins/chasm_team.so) and its unit tests;
# the codec's own tests are tests/teamlink/*.c (bin/test_team_codec) and a
# probe the cross tests drive from Python (bin/team-codec-probe).
TEAM_SCHEMA := c/plugins/team/team_link.schema
TEAM_GEN := $(GEN)/team
TEAM_GEN_STAMP := $(TEAM_GEN)/codec.stamp
CFLAGS_ALL += -I$(GEN)

$(TEAM_GEN_STAMP): $(TEAM_SCHEMA) python/tools/codegen/gen_team_codec.py python/auvlcm/team_schema.py | $(VENV_STAMP)
	@echo "gen_team_codec -> $(TEAM_GEN)"
	@$(VPY) -m tools.codegen.gen_team_codec $(TEAM_SCHEMA) $(TEAM_GEN)
	@touch $@
$(TEAM_GEN)/team_codec.h $(TEAM_GEN)/team_codec.c: $(TEAM_GEN_STAMP) ;

# Objects that include the generated header wait for it (the .d files only
# know about it after a first build).
TEAM_CODEC_USERS = $(patsubst %.c,$(1)/obj/%.o,$(wildcard c/plugins/team/*.c tests/plugins/team/*.c tests/teamlink/*.c) c/teamlink/team_front.c)

define teamlink_rules
$(1)/obj/gen/team/team_codec.o: $(TEAM_GEN)/team_codec.c Makefile
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(CFLAGS_ALL) $$(vflags) -MMD -MP -c $$< -o $$@
$(call TEAM_CODEC_USERS,$(1)): | $(TEAM_GEN_STAMP)
$(1)/plugins/chasm_team.so: $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o $(1)/obj/c/teamlink/team_front.o
$(1)/bin/test_plugin_team: $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o $(1)/obj/c/teamlink/team_front.o
$(1)/bin/test_team_codec: $(1)/obj/tests/teamlink/test_team_codec.o $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
$(1)/bin/team-codec-probe: $(1)/obj/tests/teamlink/team_codec_probe.o $(1)/obj/gen/team/team_codec.o $(1)/obj/c/teamlink/team_bits.o
	@mkdir -p $$(@D)
	$$(Q)$$(CC) $$(vflags) $$^ -o $$@ -lm
endef
$(foreach v,$(VARIANTS),$(eval $(call teamlink_rules,$(v))))

C_PROGRAMS += bin/test_team_codec bin/team-codec-probe
