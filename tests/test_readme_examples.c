/* The README's command-line transcripts are run and compared, so that they cannot go stale:
 * in every ``` block, a line "$ ./build/casteljau ..." is run with /bin/sh (./build/casteljau
 * replaced by the casteljau under test) and its standard output must equal the lines that
 * follow, up to the next such line, another "$ " line or the end of the block. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cli_run.h"

#ifndef CJ_CLI
#error "CJ_CLI must name the casteljau executable"
#endif
#ifndef CJ_README
#error "CJ_README must name README.md"
#endif

static char *read_all(const char *path) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    b[n] = '\0';
    fclose(f);
    return b;
}

/* Replaces every "./build/casteljau" in `cmd` by the executable under test. */
static void substitute(const char *cmd, char *out, size_t size) {
    static const char from[] = "./build/casteljau";
    size_t n = 0;
    while (*cmd && n + 1 < size) {
        if (!strncmp(cmd, from, sizeof from - 1)) {
            n += (size_t)snprintf(out + n, size - n, "'%s'", CJ_CLI);
            cmd += sizeof from - 1;
        } else {
            out[n++] = *cmd++;
        }
    }
    out[n < size ? n : size - 1] = '\0';
}

static int run_one(const char *cmd, const char *want, int line) {
    char full[8192];
    substitute(cmd, full, sizeof full);
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(full, &r), 0);
    int ok = r.status == 0 && !strcmp(r.out, want);
    if (!ok)
        fprintf(stderr,
                "README.md line %d: $ %s\n  exit %d\n  printed:\n%s  README shows:\n%s  stderr: "
                "%s\n",
                line, cmd, r.status, r.out, want, r.err);
    cj_cli_result_free(&r);
    return ok;
}

static void test_transcripts(void **state) {
    (void)state;
    char *text = read_all(CJ_README);
    int in_block = 0, line = 0, cmd_line = 0, checked = 0, failed = 0;
    char *cmd = NULL;
    size_t want_cap = 1 << 16, want_len = 0;
    char *want = malloc(want_cap);
    assert_non_null(want);
    want[0] = '\0';
    for (char *p = text; *p;) {
        char *nl = strchr(p, '\n');
        size_t len = nl ? (size_t)(nl - p) : strlen(p);
        ++line;
        const int fence = len >= 3 && !strncmp(p, "```", 3);
        /* Only transcripts of the tool itself run (a "$ scripts/setup.sh" would install), and
         * the printf lines that write their input files. */
        const int prompt = in_block && ((len >= 20 && !strncmp(p, "$ ./build/casteljau ", 20)) ||
                                        (len >= 9 && !strncmp(p, "$ printf ", 9)));
        const int any_prompt = in_block && len >= 2 && !strncmp(p, "$ ", 2);
        if (cmd && (fence || any_prompt)) { /* the previous command's output ends here */
            failed += !run_one(cmd, want, cmd_line);
            ++checked;
            free(cmd);
            cmd = NULL;
        }
        if (fence) {
            in_block = !in_block;
        } else if (prompt) {
            cmd = malloc(len - 1);
            assert_non_null(cmd);
            memcpy(cmd, p + 2, len - 2);
            cmd[len - 2] = '\0';
            cmd_line = line;
            want_len = 0;
            want[0] = '\0';
        } else if (cmd) {
            assert_true(want_len + len + 2 < want_cap);
            memcpy(want + want_len, p, len);
            want_len += len;
            want[want_len++] = '\n';
            want[want_len] = '\0';
        }
        p = nl ? nl + 1 : p + len;
    }
    free(cmd);
    free(want);
    free(text);
    printf("test_readme_examples: %d README transcripts run, %d differ\n", checked, failed);
    assert_true(checked >= 3); /* the parser found the transcripts */
    assert_int_equal(failed, 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_transcripts)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
