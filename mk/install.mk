# mk/install.mk: `make install` and `make uninstall` (PREFIX, LIBDIR, DATADIR, MANDIR, DESTDIR), laid out as a Debian
# packager expects: the programs a user runs (not the developer tools), libcumulo.so with its soname and the static
# library, the public header, cumulo.pc, the tables, example scenes, man pages, the example host program's source
# (as documentation), the kiosk's systemd unit and FlightGear's protocol file for `cumulo ig` (users copy it into
# $FG_ROOT/Protocol/).
BINDIR     = $(CONFIG_PREFIX)/bin
INCLUDEDIR = $(CONFIG_PREFIX)/include
PKGDATADIR = $(CONFIG_DATADIR)/cumulo
DOCDIR     = $(CONFIG_DATADIR)/doc/cumulo
# Debian's units live in /lib/systemd/system for PREFIX=/usr; elsewhere under the prefix.
UNITDIR   ?= $(if $(filter /usr,$(CONFIG_PREFIX)),/lib/systemd/system,$(CONFIG_PREFIX)/lib/systemd/system)
INSTALL   ?= install

INSTALL_PROGRAMS := $(B)/cumulo $(B)/cumulo-pt
INSTALL_DATA     := data/mie_cloud.tbl data/slab_fit_bouthors.txt data/slab_collector.txt
INSTALL_SCENES   := $(wildcard scenes/*.scene)
MAN_PAGES        := docs/man/cumulo.1 docs/man/cumulo.scene.5

$(B)/cumulo-kiosk.service: scripts/cumulo-kiosk.service.in $(B)/config.mk
	sed -e 's|@BINDIR@|$(BINDIR)|g' -e 's|@DATADIR@|$(PKGDATADIR)|g' -e 's|@UNITDIR@|$(UNITDIR)|g' $< >$@
ALL_BINS += $(B)/cumulo-kiosk.service

install: all
	$(INSTALL) -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(CONFIG_LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR) \
	    $(DESTDIR)$(PKGDATADIR)/data $(DESTDIR)$(PKGDATADIR)/scenes $(DESTDIR)$(CONFIG_MANDIR)/man1 \
	    $(DESTDIR)$(CONFIG_MANDIR)/man5 $(DESTDIR)$(UNITDIR) $(DESTDIR)$(DOCDIR)/examples \
	    $(DESTDIR)$(PKGDATADIR)/flightgear
	$(INSTALL) -m 755 $(INSTALL_PROGRAMS) $(DESTDIR)$(BINDIR)/
	$(INSTALL) -m 644 $(B)/libcumulo.so.$(VERSION) $(DESTDIR)$(CONFIG_LIBDIR)/
	ln -sf libcumulo.so.$(VERSION) $(DESTDIR)$(CONFIG_LIBDIR)/$(LIB_SONAME)
	ln -sf $(LIB_SONAME) $(DESTDIR)$(CONFIG_LIBDIR)/libcumulo.so
	$(INSTALL) -m 644 $(B)/libcumulo.a $(DESTDIR)$(CONFIG_LIBDIR)/
	$(INSTALL) -m 644 $(B)/cumulo.pc $(DESTDIR)$(CONFIG_LIBDIR)/pkgconfig/
	$(INSTALL) -m 644 include/cumulo.h $(DESTDIR)$(INCLUDEDIR)/
	$(INSTALL) -m 644 $(INSTALL_DATA) $(DESTDIR)$(PKGDATADIR)/data/
	$(INSTALL) -m 644 $(INSTALL_SCENES) $(DESTDIR)$(PKGDATADIR)/scenes/
	$(INSTALL) -m 644 data/flightgear/cumulo.xml $(DESTDIR)$(PKGDATADIR)/flightgear/
	$(INSTALL) -m 644 docs/man/cumulo.1 $(DESTDIR)$(CONFIG_MANDIR)/man1/
	$(INSTALL) -m 644 docs/man/cumulo.scene.5 $(DESTDIR)$(CONFIG_MANDIR)/man5/
	$(INSTALL) -m 644 $(B)/cumulo-kiosk.service $(DESTDIR)$(UNITDIR)/
	$(INSTALL) -m 644 examples/host_scene.c $(DESTDIR)$(DOCDIR)/examples/

# Needs the same PREFIX (and LIBDIR, DATADIR, MANDIR) as the install; reads nothing from the build.
U_PREFIX  = $(PREFIX)
U_UNITDIR = $(if $(filter /usr,$(PREFIX)),/lib/systemd/system,$(PREFIX)/lib/systemd/system)
uninstall:
	rm -f $(addprefix $(DESTDIR)$(U_PREFIX)/bin/,$(notdir $(INSTALL_PROGRAMS)))
	rm -f $(addprefix $(DESTDIR)$(LIBDIR)/,libcumulo.so libcumulo.so.$(SOVERSION) libcumulo.so.$(VERSION) \
	    libcumulo.a pkgconfig/cumulo.pc)
	rm -f $(DESTDIR)$(U_PREFIX)/include/cumulo.h
	rm -f $(DESTDIR)$(MANDIR)/man1/cumulo.1 $(DESTDIR)$(MANDIR)/man5/cumulo.scene.5
	rm -f $(DESTDIR)$(U_UNITDIR)/cumulo-kiosk.service
	rm -rf $(DESTDIR)$(DATADIR)/cumulo $(DESTDIR)$(DATADIR)/doc/cumulo
