# examples/examples.mk: the example host renderer (examples/host_scene.c), built as a program outside the library
# would be (the public header, libcumulo, EGL and GLES), run by make check (tests/gpu/test_host_scene.sh) and
# installed as documentation with the README's embedding section.
CFLAGS_EXAMPLE := $(CFLAGS_BASE) -Iinclude $(EGL_CFLAGS) $(LIB_CFLAGS)
$(eval $(call flags_rule,example,$(CC) $(CFLAGS_EXAMPLE)))

$(B)/host_scene: examples/host_scene.c $(B)/libcumulo.a $(B)/flags/example
	$(CC) $(CFLAGS_EXAMPLE) -o $@ $< $(B)/libcumulo.a $(EGL_LIBS) $(GLES_LIBS) $(LIB_LIBS)
ALL_BINS += $(B)/host_scene
