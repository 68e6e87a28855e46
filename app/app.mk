# app/app.mk: the `cumulo` program (render, bench, run, sweep): the public API of libcumulo plus platform/.
APP_SRCS := $(sort $(wildcard app/*.c))
APP_OBJS := $(APP_SRCS:%.c=$(B)/obj/%.o)
CFLAGS_APP := $(CFLAGS_BASE) -Iinclude -Iapp $(PLATFORM_CPPFLAGS) -I$(B)/gen $(LIB_CFLAGS)
$(eval $(call flags_rule,app,$(CC) $(CFLAGS_APP) $(VERSION)))

# The version, with git describe when the tree is a git checkout; rewritten only when it changes.
$(B)/gen/version.h: FORCE
	@mkdir -p $(@D); d=$$(git describe --always --dirty 2>/dev/null || echo unknown); \
	  printf '#define CU_VERSION "%s"\n#define CU_GIT_DESCRIBE "%s"\n' '$(VERSION)' "$$d" >$@.tmp; \
	  if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv -f $@.tmp $@; fi

$(B)/obj/app/%.o: app/%.c $(B)/flags/app | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_APP) -c $< -o $@

# Linked against the static library: the program runs from the build tree without an installed libcumulo.so.
$(B)/cumulo: $(APP_OBJS) $(PLATFORM_OBJS) $(B)/libcumulo.a
	$(CC) -o $@ $(APP_OBJS) $(PLATFORM_OBJS) $(B)/libcumulo.a $(PLATFORM_LIBS) $(LIB_LIBS)

ALL_BINS += $(B)/cumulo
