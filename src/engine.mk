# src/: libcumulo (the engine), the embedded shaders, and the `cumulo` program.
LIB_SRCS := src/scene.c src/noise.c src/ellipsoid.c src/density.c src/sunmap.c src/phase.c src/sky.c src/gl.c src/renderer.c src/energy.c \
            src/slabmodel.c src/slabmap.c src/collector.c src/presets.c
SHADERS  := $(sort $(wildcard shaders_gles/*.vert shaders_gles/*.frag shaders_gles/*.glsl))
LIB_OBJS := $(LIB_SRCS:%.c=$(B)/obj/%.o) $(B)/obj/gen/shaders.o
UTIL_SRCS := src/image.c
CLI_SRCS := $(wildcard src/cli/*.c)
ENGINE_CFLAGS := $(call pc_cflags,glesv2 libpng)

$(B)/gen/shaders.c: $(SHADERS) mk/embed_shaders.sh
	@mkdir -p $(dir $@)
	sh mk/embed_shaders.sh $@ $(SHADERS)

$(B)/obj/gen/shaders.o: $(B)/gen/shaders.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(ENGINE_CFLAGS) -c $< -o $@

$(B)/obj/src/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(ENGINE_CFLAGS) $(PLATFORM_CFLAGS) -DCU_INSTALL_DATA_DIR='"$(PREFIX)/share/cumulo/data"' \
	    -c $< -o $@

$(B)/obj/platform/%.o: platform/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_COMMON) $(PLATFORM_CFLAGS) -c $< -o $@

$(B)/libcumulo.a: $(LIB_OBJS)
	@rm -f $@
	ar rcs $@ $^

$(B)/libcumulo_util.a: $(UTIL_SRCS:%.c=$(B)/obj/%.o)
	@rm -f $@
	ar rcs $@ $^

$(B)/cumulo: $(CLI_SRCS:%.c=$(B)/obj/%.o) $(PLATFORM_SRCS:%.c=$(B)/obj/%.o) $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) -o $@ $^ $(PLATFORM_LIBS) $(call pc_libs,libpng) -ldl $(LDLIBS_COMMON)

ALL_BINS += $(B)/cumulo
