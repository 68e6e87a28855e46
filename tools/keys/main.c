/* tools/keys/main.c: cumulo-keys prints the scene key table (src/core/scene_keys.c) as the README's Markdown table
 * (--markdown) or as the key rows of docs/man/cumulo.scene.5 (--man); `make keys-docs` puts both in place and
 * tests/core/test_keys.sh fails when either differs. */
#include "scene_keys.h"
#include "version.h"
#include <stdio.h>
#include <string.h>

/* "number", "integer", "3 numbers", "enum", "bool". */
static void type_text(const cu_scene_key *k, char *out, size_t n)
{
    static const char *const one[] = {"number", "integer", "enum", "bool", "time"};
    static const char *const many[] = {"numbers", "integers", "enums", "bools", "times"};
    if (k->count > 1)
        snprintf(out, n, "%d %s", k->count, many[k->type]);
    else
        snprintf(out, n, "%s", one[k->type]);
}

/* The legal values: "[lo, hi]" or "(lo, hi]" for numbers (", multiple of M"), the names joined by sep otherwise;
 * each name or number between quote and quote. */
static void range_text(const cu_scene_key *k, char *out, size_t n, const char *sep, const char *quote)
{
    out[0] = 0;
    if (k->values) {
        for (int i = 0; k->values[i]; i++) {
            size_t len = strlen(out);
            snprintf(out + len, n - len, "%s%s%s%s", i ? sep : "", quote, k->values[i], quote);
        }
        return;
    }
    if (k->type == CU_KEY_TIME) {
        snprintf(out, n, "%sISO 8601 UTC, 1900..2100%s", quote, quote);
        return;
    }
    int len = snprintf(out, n, "%s%g, %g]", k->lo_open ? "(" : "[", k->lo, k->hi);
    if (k->multiple && len > 0 && (size_t)len < n)
        snprintf(out + len, n - (size_t)len, ", multiple of %d", k->multiple);
}

static void markdown(void)
{
    printf("| section | key | type | default | values | unit | meaning |\n");
    printf("| --- | --- | --- | --- | --- | --- | --- |\n");
    for (int s = 0; s < CU_SCENE_SECTION_COUNT; s++) {
        int n;
        const cu_scene_key *keys = cu_scene_section_keys(&cu_scene_sections[s], &n);
        for (int i = 0; i < n; i++) {
            const cu_scene_key *k = &keys[i];
            if (strcmp(k->section, cu_scene_sections[s].name) != 0)
                continue;
            char type[32], range[256];
            type_text(k, type, sizeof type);
            range_text(k, range, sizeof range, ", ", "`");
            printf("| %s | %s | %s | %s | %s | %s | %s |\n", k->section, k->name, type, k->def ? k->def : "—", range,
                   k->unit, k->doc);
        }
    }
}

/* Text for a roff line: a backslash is \e, a minus (user-typed values) \-, and a leading . or ' is guarded by \&. */
static void roff(const char *text, int minus)
{
    if (text[0] == '.' || text[0] == '\'')
        fputs("\\&", stdout);
    for (const char *p = text; *p; p++) {
        if (*p == '\\')
            fputs("\\e", stdout);
        else if (*p == '-' && minus)
            fputs("\\-", stdout);
        else
            putchar(*p);
    }
}

static void man(void)
{
    for (int s = 0; s < CU_SCENE_SECTION_COUNT; s++) {
        const cu_scene_section *sec = &cu_scene_sections[s];
        printf(".SS [%s]%s\n", sec->name, sec->required ? " (required)" : "");
        roff(sec->doc, 0);
        printf(".\n");
        int n;
        const cu_scene_key *keys = cu_scene_section_keys(sec, &n);
        for (int i = 0; i < n; i++) {
            const cu_scene_key *k = &keys[i];
            if (strcmp(k->section, sec->name) != 0)
                continue;
            char type[32], range[256];
            type_text(k, type, sizeof type);
            range_text(k, range, sizeof range, " | ", "");
            printf(".TP\n.B %s\n", k->name);
            printf("%s%s", type, k->values ? ": " : " in ");
            roff(range, 1);
            if (k->unit[0])
                printf(" %s", k->unit);
            printf("; default ");
            roff(k->def ? k->def : "none", 1);
            printf(".\n.br\n");
            roff(k->doc, 0);
            printf("\n");
        }
    }
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--markdown") == 0)
        markdown();
    else if (argc == 2 && strcmp(argv[1], "--man") == 0)
        man();
    else if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        printf("usage: cumulo-keys --markdown | --man\n"
               "Prints the scene key table (src/core/scene_keys.c) for README.md or docs/man/cumulo.scene.5.\n"
               "  --markdown   the README's Markdown table\n"
               "  --man        the key rows of cumulo.scene(5), in man(7) markup\n"
               "  --version    the version\n");
    else if (argc == 2 && strcmp(argv[1], "--version") == 0)
        printf("cumulo-keys %s (%s)\n", CU_VERSION, CU_GIT_DESCRIBE);
    else {
        fprintf(stderr, "usage: cumulo-keys --markdown | --man\n"
                        "prints the scene key table for README.md or docs/man/cumulo.scene.5\n");
        return 2;
    }
    return ferror(stdout) || fflush(stdout) ? 1 : 0;
}
