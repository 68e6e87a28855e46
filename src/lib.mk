# src/lib.mk: libcumulo. src/core/ (no GL: scene, geometry, density, noise, phase, sky, slab model, images) and
# src/gpu/ (the passes and the renderer), with the GLSL of shaders_gles/ embedded. Built as libcumulo-core.a (what the
# path tracer and the CPU tests link), libcumulo.a and libcumulo.so.$(SOVERSION) (exports only include/cumulo.h).
CORE_SRCS := $(sort $(wildcard src/core/*.c))
GPU_SRCS  := $(sort $(wildcard src/gpu/*.c))
SHADERS   := $(sort $(wildcard shaders_gles/*.vert shaders_gles/*.frag shaders_gles/*.glsl))
CORE_OBJS := $(CORE_SRCS:%.c=$(B)/obj/%.o)
LIB_OBJS  := $(CORE_OBJS) $(GPU_SRCS:%.c=$(B)/obj/%.o) $(B)/obj/gen/shaders.o

# The library sees its own headers and the library part of the configuration (paths.h), nothing of platform/.
LIB_CPPFLAGS := -Iinclude -Isrc/core -Isrc/gpu -I$(B)/gen/lib
CFLAGS_LIB   := $(CFLAGS_BASE) -fPIC -fvisibility=default $(LIB_CPPFLAGS) $(LIB_CFLAGS)
$(eval $(call flags_rule,lib,$(CC) $(CFLAGS_LIB)))

$(B)/gen/shaders.c: $(SHADERS) mk/embed_shaders.sh
	@mkdir -p $(dir $@)
	sh mk/embed_shaders.sh $@ $(SHADERS)

$(B)/obj/gen/shaders.o: $(B)/gen/shaders.c $(B)/flags/lib
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -c $< -o $@

$(B)/obj/src/%.o: src/%.c $(B)/flags/lib
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_LIB) -c $< -o $@

$(B)/libcumulo-core.a: $(CORE_OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

$(B)/libcumulo.a: $(LIB_OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

# The shared library exports what include/cumulo.h declares (src/libcumulo.map; tests/build checks the two agree).
LIB_SONAME := libcumulo.so.$(SOVERSION)
$(B)/libcumulo.so.$(VERSION): $(LIB_OBJS) src/libcumulo.map
	$(CC) -shared -Wl,-soname,$(LIB_SONAME) -Wl,--version-script=src/libcumulo.map -Wl,--no-undefined \
	    -o $@ $(LIB_OBJS) $(LIB_LIBS)
$(B)/$(LIB_SONAME): $(B)/libcumulo.so.$(VERSION)
	ln -sf $(notdir $<) $@
$(B)/libcumulo.so: $(B)/$(LIB_SONAME)
	ln -sf $(notdir $<) $@

# pkg-config file for the installed library, with this configuration's paths.
$(B)/cumulo.pc: src/cumulo.pc.in $(B)/config.mk
	sed -e 's|@PREFIX@|$(CONFIG_PREFIX)|g' -e 's|@LIBDIR@|$(CONFIG_LIBDIR)|g' -e 's|@VERSION@|$(VERSION)|g' \
	    -e 's|@REQUIRES_PRIVATE@|$(LIB_PC_REQUIRES)|g' $< >$@

ALL_BINS += $(B)/libcumulo-core.a $(B)/libcumulo.a $(B)/libcumulo.so $(B)/cumulo.pc
