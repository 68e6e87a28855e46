# tools/keys/keys.mk: build/cumulo-keys, a developer tool that prints the scene key table (src/core/scene_keys.c) as
# Markdown and as man(7) rows. `make keys-docs` writes both between the marker comments of README.md and
# docs/man/cumulo.scene.5; tests/core/test_keys.sh fails when they differ from what the tool prints.
$(B)/obj/tools/keys/%.o: tools/keys/%.c $(B)/flags/tools | $(B)/gen/version.h
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_TOOLS) -c $< -o $@

$(B)/cumulo-keys: $(B)/obj/tools/keys/main.o $(B)/libcumulo-core.a
	$(CC) -o $@ $^ $(LIB_LIBS)

ALL_BINS += $(B)/cumulo-keys

.PHONY: keys-docs
keys-docs: $(B)/cumulo-keys
	$(B)/cumulo-keys --markdown | sh tools/keys/splice.sh README.md '<!-- keys:begin -->' '<!-- keys:end -->'
	$(B)/cumulo-keys --man | sh tools/keys/splice.sh docs/man/cumulo.scene.5 '.\" keys:begin' '.\" keys:end'
