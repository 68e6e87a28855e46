# tests/fuzz/fuzz.mk: libFuzzer targets (tests/fuzz/fuzz_*.c), built with clang into $(B)/fuzz/ by `make fuzz`, which
# runs each for FUZZ_SECONDS from a seed corpus of scenes/, data/ and tests/fuzz/seeds/ and fails on any finding.
# Plain builds never need clang: only these goals use FUZZ_CC. `make fuzz-pending` replays the reproducers of
# tests/fuzz/pending/ against the checks that fail today (FUZZ_CHECK_PENDING in tests/fuzz/fuzz.h).
FUZZ_CC      ?= clang
FUZZ_SECONDS ?= 60
FUZZ_JOBS    ?= 2
FUZZ_TARGETS := scene set mie slab collector stdin cigi fgxp
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_CFLAGS  := -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Werror -O1 -g $(FUZZ_SAN) \
                -Iinclude -Isrc/core -Iplatform/input -Iplatform/sim -Itests/fuzz -I$(B)/gen/lib $(LIB_CFLAGS)
# What each target links besides its own file: the core library (its parsers, as the programs have them), the
# stdin command parser with the input types it fills, or the host simulations' decoders.
FUZZ_SRCS_scene     := tests/fuzz/scene_check.c $(CORE_SRCS)
FUZZ_SRCS_set       := tests/fuzz/scene_check.c $(CORE_SRCS)
FUZZ_SRCS_mie       := $(CORE_SRCS)
FUZZ_SRCS_slab      := $(CORE_SRCS)
FUZZ_SRCS_collector := $(CORE_SRCS)
FUZZ_SRCS_stdin     := platform/input/stdin_input.c platform/input/input.c platform/input/sun_control.c \
                       platform/input/knob_speed.c platform/input/clock_control.c
FUZZ_SRCS_cigi      := platform/sim/cigi.c
FUZZ_SRCS_fgxp      := platform/sim/fgfs.c platform/sim/xplane.c
$(eval $(call flags_rule,fuzz,$(FUZZ_CC) $(FUZZ_CFLAGS)))

# $(call fuzz_target,NAME,DIR,EXTRA_CFLAGS): DIR/fuzz_NAME from tests/fuzz/fuzz_NAME.c, its objects in DIR/obj.
define fuzz_target
$(2)/fuzz_$(1): tests/fuzz/fuzz_$(1).c $$(patsubst %.c,$(2)/obj/%.o,$$(FUZZ_SRCS_$(1))) $(B)/flags/fuzz
	$$(FUZZ_CC) $$(FUZZ_CFLAGS) $(3) -fsanitize=fuzzer -o $$@ $$< $$(patsubst %.c,$(2)/obj/%.o,$$(FUZZ_SRCS_$(1))) \
	    $$(LIB_LIBS)
endef
$(B)/fuzz/obj/%.o: %.c $(B)/flags/fuzz
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@
$(B)/fuzz/pending/obj/%.o: %.c $(B)/flags/fuzz
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -DFUZZ_PENDING -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@
$(foreach t,$(FUZZ_TARGETS),$(eval $(call fuzz_target,$(t),$(B)/fuzz)))
$(foreach t,$(FUZZ_TARGETS),$(eval $(call fuzz_target,$(t),$(B)/fuzz/pending,-DFUZZ_PENDING)))
-include $(shell find $(B)/fuzz -name '*.d' 2>/dev/null)

# The CIGI seeds are datagrams the host-side encoders write: `make cigi-seeds` rewrites tests/fuzz/seeds/cigi/.
$(B)/cigi_seeds: tests/sim/cigi_seeds.c tests/sim/cigi_encode.c platform/sim/cigi.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS_BASE) -Itests/sim -Iplatform/sim -o $@ $^ -lm
cigi-seeds: $(B)/cigi_seeds
	$(B)/cigi_seeds tests/fuzz/seeds/cigi

.PHONY: fuzz fuzz-build fuzz-pending cigi-seeds
fuzz-build: $(FUZZ_TARGETS:%=$(B)/fuzz/fuzz_%)
fuzz: fuzz-build
	@B=$(B) FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_JOBS=$(FUZZ_JOBS) sh tests/fuzz/run_fuzz.sh $(FUZZ_TARGETS)
fuzz-pending: $(FUZZ_TARGETS:%=$(B)/fuzz/pending/fuzz_%)
	@B=$(B) sh tests/fuzz/run_fuzz.sh --pending $(FUZZ_TARGETS)
