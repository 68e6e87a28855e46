# tools/pathtrace: the reference volumetric path tracer (build/cumulo-pt). It links the core of the library only
# (scene, density, noise, phase, sky: no GL). Tests are in tests/pathtrace/.
$(B)/obj/tools/pathtrace/%.o: tools/pathtrace/%.c $(B)/flags/tools | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_TOOLS) $(LIB_CFLAGS) -c $< -o $@

$(B)/cumulo-pt: $(B)/obj/tools/pathtrace/main.o $(B)/obj/tools/pathtrace/pt.o $(B)/libcumulo-core.a
	$(CC) -o $@ $^ $(LIB_LIBS) -lpthread

ALL_BINS += $(B)/cumulo-pt
