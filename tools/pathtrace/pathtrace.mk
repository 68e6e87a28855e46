# tools/pathtrace: the reference volumetric path tracer (build/cumulo-pt). It links the core of the library only
# (scene, density, noise, phase, sky: no GL). Tests are in tests/pathtrace/.
$(B)/obj/tools/pathtrace/%.o: tools/pathtrace/%.c $(B)/flags/tools | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_TOOLS) $(LIB_CFLAGS) -c $< -o $@

# The path tracer proper, without its command line: what the sweep and the tests link.
PT_OBJS := $(addprefix $(B)/obj/tools/pathtrace/,pt.o pt_sample.o pt_render.o)

$(B)/cumulo-pt: $(B)/obj/tools/pathtrace/main.o $(PT_OBJS) $(B)/libcumulo-core.a
	$(CC) -o $@ $^ $(LIB_LIBS) -lpthread

ALL_BINS += $(B)/cumulo-pt
