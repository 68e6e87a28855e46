# tools/pathtrace: the reference volumetric path tracer (build/cumulo-pt) and its validation tests.
PT_DIR := tools/pathtrace
PT_OBJ := $(B)/obj/tools/pathtrace
PT_CFLAGS := $(CFLAGS_COMMON) -DCU_INSTALL_DATA_DIR='"$(PREFIX)/share/cumulo/data"'
PT_LIBS := $(B)/libcumulo.a $(B)/libcumulo_util.a $(call pc_libs,libpng) -ldl $(LDLIBS_COMMON)

$(PT_OBJ)/%.o: $(PT_DIR)/%.c
	@mkdir -p $(dir $@)
	$(CC) $(PT_CFLAGS) $(call pc_cflags,cmocka) -c $< -o $@

$(B)/cumulo-pt: $(PT_OBJ)/main.o $(PT_OBJ)/pt.o $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) -o $@ $(PT_OBJ)/main.o $(PT_OBJ)/pt.o $(PT_LIBS)

$(B)/test_pathtrace: $(PT_OBJ)/test_pt.o $(PT_OBJ)/pt.o $(B)/libcumulo.a $(B)/libcumulo_util.a
	$(CC) -o $@ $(PT_OBJ)/test_pt.o $(PT_OBJ)/pt.o $(call pc_libs,cmocka) $(PT_LIBS)

ALL_BINS += $(B)/cumulo-pt
CHECK_TESTS += $(B)/test_pathtrace $(PT_DIR)/test_pt_cli.sh
